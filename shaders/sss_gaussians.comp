#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS, gaussians mode: each Gaussian of the material's fit as its own
// separable blur, incrementally. Pass (g, direction) blurs by the 1D Gaussian of variance
// v_g - v_{g-1} (the input already holds E blurred by v_{g-1}); the vertical pass also
// accumulates w_g x (E * G(v_g)) into accum_img (written, not added, for g = 0). Exact
// for a flat surface up to sampling: integer-pixel taps (stride 1, or wider for wide
// Gaussians), weights normalised over the taps.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D surface_tex;  // depth mm, material id
layout(set = 0, binding = 4) uniform sampler2D input_tex;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D output_img;
layout(set = 0, binding = 6, rgba16f) uniform image2D accum_img;
layout(push_constant) uniform Push { BlurPush blur; };

#include "shared/sss.glsl"
#include "shared/gaussian_blur.glsl"

// x: distance from the camera plane in mm, y: material id (-1: background).
vec2 surface_at(ivec2 q) { return texelFetch(surface_tex, q, 0).xy; }


void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(frame.rect.xy);  // the geometry's rect
  if (any(greaterThanEqual(p, ivec2(frame.rect.zw)))) return;
  ivec2 lo = ivec2(frame.rect.xy), hi = ivec2(frame.rect.zw) - 1;  // border: background
  vec2 dir = blur.direction.xy;
  int g = int(blur.direction.z);
  bool vertical = dir.y > 0.5;
  vec2 here = surface_at(p);
  int id = int(here.y);
  bool scatters = id >= 0 && materials[id].scatters != 0 &&
                  g < materials[id].gaussian_count;
  // Pixels that do not scatter (at this step) are left unwritten: taps are fetched at
  // whole pixels, a tap on another material or the background falls back to the centre
  // value without using its own, a pixel of the same material is in the same state, and
  // composite reads accum only where a material scatters.
  if (!scatters) return;
  vec3 center = texelFetch(input_tex, p, 0).rgb;
  float width_mm = materials[id].range_mm;
  float z = here.x;
  // The surface's depth slope along dir from the centre's two neighbours, and the pixels
  // per mm of surface: the camera plane's over the foreshortening (sss.glsl).
  float ppm_plane = pixels_per_mm(dir, z);
  vec2 s_minus = surface_at(clamp(p - ivec2(dir), lo, hi)), s_plus = surface_at(clamp(p + ivec2(dir), lo, hi));
  float slope = depth_slope(s_minus.x - z, int(s_minus.y) == id, s_plus.x - z, int(s_plus.y) == id, ppm_plane);
  float sigma_px = sqrt(max(variance(id, g) - variance(id, g - 1), 0.0)) * ppm_plane / foreshortening(slope);
  float z_per_px = slope / ppm_plane;  // the tangent plane's depth change per pixel
  vec3 result = center;
  GaussianTaps taps = gaussian_taps(sigma_px);
  if (taps.blurs) {
    vec3 sum = center;
    float weight_sum = 1.0;
    for (int k = -taps.half_taps; k <= taps.half_taps; ++k) {
      if (k == 0) continue;
      float offset = float(k * taps.stride);
      ivec2 q = clamp(p + ivec2(dir * offset), lo, hi);
      vec2 there = surface_at(q);
      vec3 value = follow_surface(texelFetch(input_tex, q, 0).rgb, center, int(there.y), id,
                                  there.x, z + z_per_px * offset, width_mm);
      float weight = exp(-offset * offset * taps.inv_two_var);
      sum += weight * value;
      weight_sum += weight;
    }
    result = sum / weight_sum;
  }
  imageStore(output_img, p, vec4(result, 1.0));
  if (vertical) {
    vec3 accum = g == 0 ? vec3(0.0) : imageLoad(accum_img, p).rgb;
    imageStore(accum_img, p, vec4(accum + materials[id].gauss_weights[g].rgb * result, 1.0));
  }
}
