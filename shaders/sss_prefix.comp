#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS, separable mode: the running sums each 1D pass reads (issue 20 part 3,
// "separable streaks"). One invocation walks one line of the geometry's rect along
// blur.direction (rows for the horizontal pass, columns for the vertical one) and writes,
// per pixel, the sum of the input's rgb over its run up to and including the pixel, and
// in alpha the run's first pixel (its coordinate along the line).
//
// A run is a stretch of one material's surface without an occluding edge: it ends where
// the surface key's material changes (another material, the background) and at an
// occluding edge, where the depth step between two neighbours departs from the step
// before by more than a quarter of the material's follow-surface width (kernel.y). The blur (sss_separable.comp) averages the input over a tap's
// whole cell from two of these sums when the cell lies in one run, and falls back to its
// point sample otherwise, so the average never mixes two surfaces that follow surface
// keeps apart. Sums restart with every run, so their magnitude, and their float32
// rounding, is that of one run rather than of the whole line.
//
// One invocation per line and a serial walk: 2 x (width + height) sequential reads per
// frame, a fraction of the blur's ~2 x taps x 2 fetches per pixel.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_1D) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D input_tex;  // texelFetch: rgb value, a key
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D prefix_img;
layout(push_constant) uniform Push { BlurPush blur; };

#include "shared/sss.glsl"

void main() {
  bool vertical = blur.direction.y > 0.5;
  ivec2 lo = ivec2(frame.rect.xy), hi = ivec2(frame.rect.zw);  // hi exclusive
  int line = int(gl_GlobalInvocationID.x) + (vertical ? lo.x : lo.y);
  if (line >= (vertical ? hi.x : hi.y)) return;
  int first = vertical ? lo.y : lo.x, end = vertical ? hi.y : hi.x;
  vec3 sum = vec3(0.0);
  int run_start = first;
  int prev_id = -2, prev2_id = -2;  // the two pixels before k
  float prev_z = 0.0, prev2_z = 0.0;
  for (int k = first; k < end; ++k) {
    ivec2 p = vertical ? ivec2(line, k) : ivec2(k, line);
    vec4 v = texelFetch(input_tex, p, 0);
    int id = key_material(v.a);
    float z = id >= 0 ? key_depth(v.a, id) : 0.0;
    // An occluding edge: the depth step to the previous pixel departs from the one before
    // it (a plane, however tilted, steps evenly) by more than a quarter of the width; with
    // no step before it (the material begins at k - 1), the step itself is measured.
    float tolerance = id >= 0 ? 0.25 * materials[id].kernel.y : 0.0;
    float before = prev2_id == id ? prev_z - prev2_z : 0.0;
    bool same = id >= 0 && id == prev_id && abs((z - prev_z) - before) <= tolerance;
    if (!same) {
      sum = vec3(0.0);
      run_start = k;
    }
    sum += v.rgb;
    imageStore(prefix_img, p, vec4(sum, float(run_start)));
    prev2_id = prev_id;
    prev2_z = prev_z;
    prev_id = id;
    prev_z = z;
  }
}
