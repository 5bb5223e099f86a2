#version 460
#extension GL_GOOGLE_include_directive : require
// Anti-aliasing (RenderOptions::antialias == Fxaa): a post-process over the display image
// after composite, the method of Lottes' FXAA (T. Lottes, "FXAA", NVIDIA white paper,
// 2009; the quality preset of FXAA 3.11: luma contrast test, subpixel blend, an edge-end
// search along the edge with growing strides). Written from that description:
//
//  1. The local contrast of the pixel's 4-neighbourhood luma (perceptual: the display's
//     sRGB codes). Below max(kContrastMin, kContrastRel x brightest) the pixel is not on
//     an edge and is left as composite wrote it (a flat region is bit for bit the same).
//  2. The edge's orientation from second differences across rows and columns of the 3x3
//     block, and its side: the neighbour across the edge with the larger luma step.
//  3. From the point halfway to that neighbour, a walk along the edge both ways (bilinear
//     taps, which average the two sides) until the average moves by a quarter of the step:
//     the edge's two ends. A pixel nearer one end than the other lies where a staircase
//     step should be a ramp: it blends towards the neighbour by 1/2 - distance / span
//     (0 at the middle of a step, 1/2 at its end), if that end's luma moves away from the
//     pixel's side of the edge, as a step's does.
//  4. Single-pixel features (a 1-px highlight, a thin wire) have no long edge: they blend
//     by how much the pixel stands out of its 3x3 low-pass, kSubpixel at most.
//  5. The result is a bilinear tap of the source moved by the larger of the two blends
//     across the edge, alpha included. Without RenderOptions::background the background
//     is rgba 0, so at a silhouette the result is the frame over black (what the window
//     shows) with alpha its coverage: premultiplied, which Renderer::read_display() divides
//     out; with one, alpha is 1 everywhere and the silhouette blends with that colour.
//
// Reads `source` (a copy of display made just before, so no pixel reads a neighbour this
// pass already wrote) and writes `display_img`.
#include "shared/config.h"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform sampler2D source;  // bilinear, clamp to edge
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D display_img;

// FXAA 3.11's quality defaults (the white paper's "high quality" thresholds).
const float kContrastRel = 0.125;   // edge when the luma range exceeds 1/8 of the brightest
const float kContrastMin = 0.0312;  // and 1/32 absolute (dark regions are left alone)
const float kSubpixel = 0.75;       // strength of the single-pixel blend
const int kSteps = 12;              // edge-end search: up to 12 taps each way, 29 px far
const float kStride[kSteps] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);

float luma(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }  // Rec. 601 weights

ivec2 size;
float luma_at(ivec2 p) { return luma(texelFetch(source, clamp(p, ivec2(0), size - 1), 0).rgb); }
float luma_uv(vec2 uv) { return luma(textureLod(source, uv, 0.0).rgb); }

void main() {
  size = textureSize(source, 0);
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  const vec4 centre = texelFetch(source, p, 0);
  const float m = luma(centre.rgb);
  // Image rows grow downwards: "up" is y - 1.
  const float up = luma_at(p + ivec2(0, -1)), down = luma_at(p + ivec2(0, 1));
  const float left = luma_at(p + ivec2(-1, 0)), right = luma_at(p + ivec2(1, 0));
  const float lo = min(m, min(min(up, down), min(left, right)));
  const float hi = max(m, max(max(up, down), max(left, right)));
  const float range = hi - lo;
  if (range < max(kContrastMin, hi * kContrastRel)) return;  // display keeps composite's value

  const float ul = luma_at(p + ivec2(-1, -1)), ur = luma_at(p + ivec2(1, -1));
  const float dl = luma_at(p + ivec2(-1, 1)), dr = luma_at(p + ivec2(1, 1));

  // 4. How far the pixel stands out of its 3x3 low-pass (edge neighbours weigh 2).
  const float low_pass = (2.0 * (up + down + left + right) + ul + ur + dl + dr) / 12.0;
  const float stand_out = smoothstep(0.0, 1.0, clamp(abs(low_pass - m) / range, 0.0, 1.0));
  const float sub_blend = stand_out * stand_out * kSubpixel;

  // 2. Orientation: a horizontal edge changes luma down the columns.
  const float across_rows = abs(ul - 2.0 * left + dl) + 2.0 * abs(up - 2.0 * m + down) +
                            abs(ur - 2.0 * right + dr);
  const float across_cols = abs(ul - 2.0 * up + ur) + 2.0 * abs(left - 2.0 * m + right) +
                            abs(dl - 2.0 * down + dr);
  const bool horizontal = across_rows >= across_cols;
  const vec2 texel = 1.0 / vec2(size);
  const float before = horizontal ? up : left, after = horizontal ? down : right;
  const bool towards_before = abs(before - m) >= abs(after - m);
  const float other = towards_before ? before : after;
  const float step_luma = abs(other - m);
  vec2 across = horizontal ? vec2(0.0, texel.y) : vec2(texel.x, 0.0);
  if (towards_before) across = -across;
  const vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);

  // 3. The edge's ends, on the line halfway between the pixel and its neighbour.
  const vec2 uv = (vec2(p) + 0.5) * texel;
  const vec2 on_edge = uv + 0.5 * across;
  const float edge_mean = 0.5 * (m + other);
  const float found = 0.25 * step_luma;
  vec2 uv_neg = on_edge - along * kStride[0], uv_pos = on_edge + along * kStride[0];
  float end_neg = luma_uv(uv_neg) - edge_mean, end_pos = luma_uv(uv_pos) - edge_mean;
  bool done_neg = abs(end_neg) >= found, done_pos = abs(end_pos) >= found;
  for (int i = 1; i < kSteps && !(done_neg && done_pos); ++i) {
    if (!done_neg) {
      uv_neg -= along * kStride[i];
      end_neg = luma_uv(uv_neg) - edge_mean;
      done_neg = abs(end_neg) >= found;
    }
    if (!done_pos) {
      uv_pos += along * kStride[i];
      end_pos = luma_uv(uv_pos) - edge_mean;
      done_pos = abs(end_pos) >= found;
    }
  }
  const float to_neg = horizontal ? uv.x - uv_neg.x : uv.y - uv_neg.y;
  const float to_pos = horizontal ? uv_pos.x - uv.x : uv_pos.y - uv.y;
  const bool neg_nearer = to_neg < to_pos;
  const float nearest_end = min(to_neg, to_pos);
  const float span = to_neg + to_pos;
  // A step's end: there the luma crosses to the other side of the edge's mean from the
  // pixel's own.
  const bool pixel_below = m - edge_mean < 0.0;
  const bool step_end = ((neg_nearer ? end_neg : end_pos) < 0.0) != pixel_below;
  const float edge_blend = step_end ? 0.5 - nearest_end / span : 0.0;

  // 5.
  const float blend = max(edge_blend, sub_blend);
  imageStore(display_img, p, textureLod(source, uv + blend * across, 0.0));
}
