#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS, separable mode (Jimenez 2015): one 1D pass of the material's kernel
// (offsets in mm, RGB weights summing to 1) along direction.xy. Run horizontally on the
// irradiance (-> line_img), then vertically on the result, where it also composites the
// pixels it scattered (composite.glsl: x total reflectance x albedo / pi + specular ->
// hdr, display); composite.comp does the other pixels.
//
// The input is rgba32f: rgb the value, alpha the surface key (sss.glsl: depth in mm +
// material id x stride), so a texel read once carries the value and what follow surface
// needs: the key difference from the centre's tangent plane, over the kernel's range,
// lerps a value toward the centre's, and a texel of another material or the background
// (key difference > any range) is the centre value.
//
// Each tap stands for its cell of the kernel (profiles::SeparableKernel) and takes the
// input's mean over the cell, from sss_prefix.comp's running sums at the cell's two ends,
// wherever the cell is at least a pixel wide and lies on one run of surface; elsewhere it
// is the bilinear point sample at the tap. The point sample alone made a light edge a
// staircase of 17 steps, up to tens of pixels apart at the bunny's scale, which the
// vertical pass drew out into streaks.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D albedo_tex;    // vertical: composite
layout(set = 0, binding = 3) uniform sampler2D specular_tex;  // vertical: composite
layout(set = 0, binding = 4) uniform sampler2D input_tex;     // texelFetch
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D line_img;  // horizontal
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D hdr_img;   // vertical
layout(set = 0, binding = 7, rgba8) uniform writeonly image2D display_img;
// The scattered debug view only (blur.direction.z = 1): R * E of the pixels it scattered.
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D scattered_img;
// sss_prefix.comp's running sums of input_tex along the pass's lines: rgb the sum over
// the run up to and including the pixel, alpha the run's first pixel.
layout(set = 0, binding = 9) uniform sampler2D prefix_tex;  // texelFetch
layout(push_constant) uniform Push { BlurPush blur; };

#include "shared/sss.glsl"
#include "shared/composite.glsl"
#include "shared/cell_mean.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(frame.rect.xy);  // the geometry's rect
  if (any(greaterThanEqual(p, ivec2(frame.rect.zw)))) return;
  bool vertical = blur.direction.y > 0.5;
  vec4 center = texelFetch(input_tex, p, 0);
  int id = key_material(center.a);
  // Pixels that do not scatter: the horizontal pass copies them (value and key: the
  // vertical pass's taps read every pixel), the vertical pass leaves them to composite.
  if (id < 0 || materials[id].scatters == 0) {
    if (!vertical) imageStore(line_img, p, center);
    return;
  }
  vec2 dir = blur.direction.xy;
  float z = key_depth(center.a, id);
  ivec2 lo = ivec2(frame.rect.xy), hi = ivec2(frame.rect.zw) - 1;  // border: background
  ivec2 step = ivec2(dir);
  // The surface's depth slope along dir from the centre's two neighbours' keys, and the
  // pixels per mm of surface: the camera plane's over the foreshortening (sss.glsl).
  float ppm_plane = pixels_per_mm(dir, z);
  float slope = key_depth_slope(texelFetch(input_tex, clamp(p - step, lo, hi), 0).a,
                                texelFetch(input_tex, clamp(p + step, lo, hi), 0).a, id, z, ppm_plane);
  float ppm = ppm_plane / foreshortening(slope);
  float key_per_px = slope / ppm_plane;  // the tangent plane's depth (key) change per pixel
  float inv_width = 1.0 / materials[id].range_mm;
  int taps = materials[id].separable_taps;
  vec3 sum = vec3(0.0);
  // The cell boundaries: midpoints between neighbouring taps (profiles::SeparableKernel:
  // tap i's weight is the marginal integrated over its cell); the outermost cells, which
  // reach to infinity there, end as far beyond their tap as they begin before it.
  vec4 tap = materials[id].taps[0];
  vec4 next = materials[id].taps[1];
  CellEdge lower = cell_edge(p, step, lo, hi, (1.5 * tap.w - 0.5 * next.w) * ppm);
  float previous_offset = tap.w;
  for (int i = 0; i < taps; ++i) {
    // next: tap i + 1, or for the last tap the mirror of tap i - 1 about it.
    if (i > 0) tap = next;
    next = i + 1 < taps ? materials[id].taps[i + 1] : vec4(0.0, 0.0, 0.0, 2.0 * tap.w - previous_offset);
    previous_offset = tap.w;
    CellEdge upper = cell_edge(p, step, lo, hi, 0.5 * (tap.w + next.w) * ppm);
    vec3 value;
    if (one_run(lower, upper)) {
      // The cell's mean: the run's sums at its two ends, over its width. A tap whose cell
      // spans many pixels thus weighs all of them, and a light edge crossing the cell moves
      // the tap's value continuously instead of in one step: the 17-tap kernel's response
      // to an edge is M interpolated linearly between the cell boundaries, where the point
      // sample gave a staircase (the vertical streaks in the bunny's shadow).
      // Follow surface as for a point tap, with the mean of the two end pixels' distances
      // from the centre's tangent plane (0 on a plane, however tilted).
      if (key_material(upper.texel.a) != id) {
        value = center.rgb;
      } else {
        float off_plane = 0.5 * (abs(lower.texel.a - (center.a + key_per_px * float(lower.m))) +
                                 abs(upper.texel.a - (center.a + key_per_px * float(upper.m))));
        value = mix(cell_mean(lower, upper), center.rgb, clamp(off_plane * inv_width, 0.0, 1.0));
      }
    } else {
      // Linear interpolation along dir between the two texels around the tap (the tap
      // sits on the pixel row or column, so this is the bilinear sample), each replaced
      // first by follow surface: lerped toward the centre by its key's distance from the
      // centre's tangent plane over the range (sss.glsl), the centre value itself on
      // another material or the background. Cells under a pixel wide (no staircase at
      // that spacing) and cells across an occluding edge or a material's border.
      float t = tap.w * ppm;  // in pixels from p
      float f = floor(t);
      vec4 s0 = texelFetch(input_tex, clamp(p + step * int(f), lo, hi), 0);
      vec4 s1 = texelFetch(input_tex, clamp(p + step * int(f + 1.0), lo, hi), 0);
      float plane0 = center.a + key_per_px * f, plane1 = center.a + key_per_px * (f + 1.0);
      vec3 v0 = mix(s0.rgb, center.rgb, clamp(abs(s0.a - plane0) * inv_width, 0.0, 1.0));
      vec3 v1 = mix(s1.rgb, center.rgb, clamp(abs(s1.a - plane1) * inv_width, 0.0, 1.0));
      value = mix(v0, v1, t - f);
    }
    sum += tap.rgb * value;
    lower = upper;
  }
  if (!vertical) {
    imageStore(line_img, p, vec4(sum, center.a));
    return;
  }
  vec3 diffuse = materials[id].total_reflectance * sum;
  if (blur.direction.z > 0.5) imageStore(scattered_img, p, vec4(diffuse, 1.0));
  vec4 albedo_id = texelFetch(albedo_tex, p, 0);
  vec3 L = composite_radiance(id, albedo_id.rgb, diffuse,
                              texelFetch(specular_tex, p, 0));
  imageStore(hdr_img, p, vec4(L, 1.0));
  imageStore(display_img, p, vec4(display_encode(L), 1.0));
}
