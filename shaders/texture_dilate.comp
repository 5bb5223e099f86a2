#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, seam dilation (d'Eon & Luebke 2007): texels no triangle covers take the
// mean of the covered texels on the nearest ring (Chebyshev distance 1 ..
// SSS_TEXTURE_DILATE_TEXELS) that lie on one island (the first one met), for irradiance
// and stretch alike, so that the final bilinear lookup near an island's border reads the
// border's values instead of black. Their island id is stored negated: the blur treats
// them as off the island (its taps there take the point reflection) and leaves them as
// they are. Covered texels (the island and its seam gutter) are copied.
#include "shared/frame.h"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform sampler2D raw_irradiance_tex;  // rgb E, a island + 1 (0 empty)
layout(set = 0, binding = 1) uniform sampler2D raw_stretch_tex;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D irradiance_img;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D stretch_img;

void main() {
  ivec2 size = textureSize(raw_irradiance_tex, 0);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 e = texelFetch(raw_irradiance_tex, p, 0);
  if (e.a > 0.5) {
    imageStore(irradiance_img, p, e);
    imageStore(stretch_img, p, texelFetch(raw_stretch_tex, p, 0));
    return;
  }
  for (int r = 1; r <= SSS_TEXTURE_DILATE_TEXELS; ++r) {
    vec3 sum_e = vec3(0.0);
    vec4 sum_s = vec4(0.0);
    float island = 0.0, count = 0.0;
    for (int k = 0; k < 8 * r; ++k) {  // the ring's texels, walked around its square
      int side = k / (2 * r), t = k % (2 * r) - r;
      ivec2 o = side == 0 ? ivec2(t, -r) : side == 1 ? ivec2(r, t) : side == 2 ? ivec2(-t, r) : ivec2(-r, -t);
      ivec2 q = p + o;
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 v = texelFetch(raw_irradiance_tex, q, 0);
      if (v.a < 0.5 || (island > 0.0 && v.a != island)) continue;
      island = v.a;
      sum_e += v.rgb;
      sum_s += texelFetch(raw_stretch_tex, q, 0);
      count += 1.0;
    }
    if (count > 0.0) {
      imageStore(irradiance_img, p, vec4(sum_e / count, -island));  // marked: not surface
      imageStore(stretch_img, p, sum_s / count);
      return;
    }
  }
  imageStore(irradiance_img, p, vec4(0.0));
  imageStore(stretch_img, p, vec4(0.0));
}
