#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS, separable mode (Jimenez 2015): one 1D pass of the material's kernel
// (offsets in mm, RGB weights summing to 1) along direction.xy. Run horizontally on the
// irradiance, then vertically on the result; composite multiplies by the total
// reflectance.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D surface_tex;  // depth mm, material id
layout(set = 0, binding = 4) uniform sampler2D input_tex;  // bilinear
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D output_img;
layout(push_constant) uniform Push { BlurPush blur; };

#include "shared/sss.glsl"

vec3 convolve(int id, ivec2 p, ivec2 size, float z, vec3 center) {
  vec2 dir = blur.direction.xy;
  float ppm = pixels_per_mm(dir, z);
  float width_mm = materials[id].kernel.y;
  int taps = int(materials[id].kernel.x);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < taps; ++i) {
    vec4 tap = materials[id].taps[i];
    // Linear interpolation along dir between the two texels around the tap (the tap
    // sits on the pixel row or column, so this is the bilinear sample); a texel of
    // another material or the background is replaced by the centre value first.
    float t = tap.w * ppm;  // in pixels from p
    float f = floor(t);
    ivec2 q0 = clamp(p + ivec2(dir * f), ivec2(0), size - 1);
    ivec2 q1 = clamp(p + ivec2(dir * (f + 1.0)), ivec2(0), size - 1);
    vec3 v0 = center, v1 = center;
    if (q0 != p) {
      vec2 there = surface_at(q0);
      v0 = follow_surface(texelFetch(input_tex, q0, 0).rgb, center, int(there.y), id, there.x, z, width_mm);
    }
    if (q1 != p) {
      vec2 there = surface_at(q1);
      v1 = follow_surface(texelFetch(input_tex, q1, 0).rgb, center, int(there.y), id, there.x, z, width_mm);
    }
    vec3 value = mix(v0, v1, t - f);
    sum += tap.rgb * value;
  }
  return sum;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(frame.viewport.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec2 here = surface_at(p);
  int id = int(here.y);
  // Pixels that do not scatter: the horizontal pass copies them (the vertical pass's
  // bilinear taps may touch them at silhouettes); the vertical pass leaves them unwritten,
  // as composite reads its output only where a material scatters.
  if (id < 0 || materials[id].reflectance.w < 0.5) return;
  vec3 center = texelFetch(input_tex, p, 0).rgb;
  vec3 sum = convolve(id, p, size, here.x, center);
  imageStore(output_img, p, vec4(sum, 1.0));
}
