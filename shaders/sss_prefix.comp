#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS: the running sums the 1D blurs read (issue 20 part 3, "separable
// streaks"; renderer/LinePrefix.h). One invocation walks one line of the geometry's rect
// along blur.direction (rows for a horizontal pass, columns for a vertical one) and
// writes, per pixel, the sum of the input's rgb over its run up to and including the
// pixel, and in alpha the run's first pixel (its coordinate along the line).
//
// A run is a stretch of one material's surface without an occluding edge: it ends where
// the material changes (another material, the background; lighting.comp's surface
// image) and at an occluding edge, where the depth step between two neighbours departs
// from the step before by more than a quarter of the material's follow-surface width
// (kernel.y). The separable blur (sss_separable.comp) averages the input over a tap's
// whole cell from two of these sums when the cell lies in one run, and falls back to a
// point sample otherwise (shared/cell_mean.glsl), so the average never mixes two
// surfaces that follow surface keeps apart. Sums restart with every run, so their
// magnitude, and their float32 rounding, is that of one run rather than of the whole
// line.
//
// One invocation per line and a serial walk: two fetches per pixel and pass, against the
// blur's ~2 per tap (~2 ms of the pass's ~49 at 960x540 on lavapipe).
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_1D) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D input_tex;  // texelFetch: rgb the value
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D prefix_img;
// lighting.comp's: x distance from the camera plane in mm, y material id (-1: none).
layout(set = 0, binding = 4) uniform sampler2D surface_tex;
layout(push_constant) uniform Push { BlurPush blur; };


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
    vec3 v = texelFetch(input_tex, p, 0).rgb;
    vec2 surface = texelFetch(surface_tex, p, 0).xy;
    int id = int(surface.y);
    float z = surface.x;
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
    sum += v;
    imageStore(prefix_img, p, vec4(sum, float(run_start)));
    prev2_id = prev_id;
    prev2_z = prev_z;
    prev_id = id;
    prev_z = z;
  }
}
