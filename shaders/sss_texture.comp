#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, the blur (d'Eon & Luebke 2007): the object's dilated irradiance atlas
// convolved with each Gaussian of its material's fit, incrementally: step g blurs the
// previous step's result by the 1D Gaussian of variance v_g - v_{g-1} along u, then along
// v (a 2D Gaussian is separable, and G(a) * G(b) = G(a + b)); the v pass also accumulates
// w_g x (E * G(v_g)) into accum_img (written, not added, for g = 0), which the final
// lookup (texture_gather.frag) reads. The stretch map turns mm into texels at each texel:
// sigma_texels = sqrt(v_g - v_{g-1}) / (mm per texel along the pass's axis).
//
// Seams: a tap past the island's border and its seam gutter (another island, a dilated
// or empty texel, or off the texture) has no surface value in this atlas; the surface goes on in another island.
// Taking the centre's value there (the screen path's rule at a material boundary) makes
// the kernel one-sided at a seam, which shifts a gradient g by about 0.4 g sigma on each
// side in opposite directions: a visible step along the seam. Instead the tap takes the
// point reflection about the centre, 2 c - f(p - k), which is exact for irradiance that
// is linear across the seam, so both sides see an unbiased blur to first order (and the
// centre's value when the mirrored tap is off the island too; clamped at 0).
#include "shared/frame.h"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 1) uniform sampler2D stretch_tex;  // x mm per texel along u, y along v
layout(set = 0, binding = 2) uniform sampler2D input_tex;    // rgb value, a island + 1 (0 empty)
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D output_img;
layout(set = 0, binding = 4, rgba16f) uniform image2D accum_img;
layout(push_constant) uniform Push { TexturePush blur; };

// The texel's value when it lies on the centre's island, else the point reflection.
vec4 on_island(ivec2 q, float island, ivec2 size) {
  if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) return vec4(0.0);
  vec4 t = texelFetch(input_tex, q, 0);
  return t.a == island ? vec4(t.rgb, 1.0) : vec4(0.0);
}
vec3 island_value(ivec2 q, ivec2 mirror, vec4 center, ivec2 size) {
  vec4 t = on_island(q, center.a, size);
  if (t.a > 0.5) return t.rgb;
  vec4 m = on_island(mirror, center.a, size);
  return m.a > 0.5 ? max(2.0 * center.rgb - m.rgb, vec3(0.0)) : center.rgb;
}

#include "shared/gaussian_blur.glsl"

void main() {
  ivec2 size = textureSize(input_tex, 0);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  ivec2 dir = ivec2(blur.direction.xy);
  int g = int(blur.direction.z);
  int id = int(blur.direction.w);
  bool vertical = dir.y > 0;
  vec4 center = texelFetch(input_tex, p, 0);
  vec3 result = center.rgb;
  if (center.a > 0.5) {
    float mm_per_texel = vertical ? texelFetch(stretch_tex, p, 0).y : texelFetch(stretch_tex, p, 0).x;
    float sigma = sqrt(max(variance(id, g) - variance(id, g - 1), 0.0)) / max(mm_per_texel, 1e-9);
    sigma = min(sigma, 0.25 * float(size.x));  // a pole's texels: next to no surface per texel
    GaussianTaps taps = gaussian_taps(sigma);
    if (taps.blurs) {
      vec3 sum = center.rgb;
      float weight_sum = 1.0;
      for (int k = -taps.half_taps; k <= taps.half_taps; ++k) {
        if (k == 0) continue;
        float offset = float(k * taps.stride);
        float weight = exp(-offset * offset * taps.inv_two_var);
        ivec2 step = dir * (k * taps.stride);
        sum += weight * island_value(p + step, p - step, center, size);
        weight_sum += weight;
      }
      result = sum / weight_sum;
    }
  }
  imageStore(output_img, p, vec4(result, center.a));
  if (vertical) {
    vec3 accum = g == 0 ? vec3(0.0) : imageLoad(accum_img, p).rgb;
    imageStore(accum_img, p, vec4(accum + materials[id].gauss_weights[g].rgb * result, center.a));
  }
}
