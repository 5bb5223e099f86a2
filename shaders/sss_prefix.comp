#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space SSS: the running sums the 1D blurs read (issue 20 part 3, "separable
// streaks"; renderer/LinePrefix.h). Along each line of the geometry's rect in
// blur.direction (rows for a horizontal pass, columns for a vertical one) it writes, per
// pixel, the sum of the input's rgb over its run up to and including the
// pixel, and in alpha the run's first pixel (its coordinate along the line).
//
// A run is a stretch of one material's surface without an occluding edge: it ends where
// the material changes (another material, the background; lighting.comp's surface
// image) and at an occluding edge, where the depth step between two neighbours departs
// from the step before by more than a quarter of the material's follow-surface width
// (GpuMaterial::range_mm). The separable blur (sss_separable.comp) averages the input over a tap's
// whole cell from two of these sums when the cell lies in one run, and falls back to a
// point sample otherwise (shared/cell_mean.glsl), so the average never mixes two
// surfaces that follow surface keeps apart. Sums restart with every run, so their
// magnitude, and their float32 rounding, is that of one run rather than of the whole
// line.
//
// One workgroup per line, kPrefixThreads invocations, each owning a chunk of consecutive
// pixels: a segmented scan. Each invocation walks its chunk once for its runs' breaks and
// the sum since its last break; one invocation carries those across the chunks in order;
// each walks its chunk again from the carried sum and run start and writes. The runs and
// sums are the serial walk's (the sums' float32 rounding differs by association only).
// One invocation walking each whole line kept only 540 threads busy on a GPU that wants
// tens of thousands: the separable pass took 0.22 ms on an H200 at 960x540 (0.03 with
// point taps); with the scan 0.08 (1920x1080: 0.62 -> 0.23; bench/frame/bench_frame). On
// lavapipe, which runs a workgroup's barriers on CPU threads, it costs 5 ms more (47 -> 52).
#include "shared/frame.h"
#include "shared/common.glsl"

#define kPrefixThreads 128
layout(local_size_x = kPrefixThreads) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D input_tex;  // texelFetch: rgb the value
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D prefix_img;
// lighting.comp's: x distance from the camera plane in mm, y material id (-1: none).
layout(set = 0, binding = 4) uniform sampler2D surface_tex;
layout(push_constant) uniform Push { BlurPush blur; };

shared vec3 chunk_tail[kPrefixThreads];   // sum from the chunk's last run start (or its start) to its end
shared int chunk_start[kPrefixThreads];   // its last run start, -1: no run starts in it
shared vec3 carry_sum[kPrefixThreads];    // the sum before the chunk's first pixel, within its run
shared int carry_start[kPrefixThreads];   // that run's start

bool g_vertical;
int g_line;

ivec2 at(int k) { return g_vertical ? ivec2(g_line, k) : ivec2(k, g_line); }

// The walk's state: the two pixels before k.
struct Walk {
  int prev_id, prev2_id;
  float prev_z, prev2_z;
};

// Whether pixel k (its surface `surface`) starts a run after the pixels in w, and w moved
// on past k. An occluding edge: the depth step to the previous pixel departs from the step
// before it (a plane, however tilted, steps evenly) by more than a quarter of the width;
// with no step before it (the material begins at k - 1), the step itself is measured.
bool starts_run(inout Walk w, vec2 surface) {
  int id = int(surface.y);
  float z = surface.x;
  float tolerance = id >= 0 ? 0.25 * materials[id].range_mm : 0.0;
  float before = w.prev2_id == id ? w.prev_z - w.prev2_z : 0.0;
  bool same = id >= 0 && id == w.prev_id && abs((z - w.prev_z) - before) <= tolerance;
  w.prev2_id = w.prev_id;
  w.prev2_z = w.prev_z;
  w.prev_id = id;
  w.prev_z = z;
  return !same;
}

// The state before pixel k of a line that begins at `first`: its two predecessors, or
// none (-2) before the line.
Walk walk_before(int k, int first) {
  Walk w = Walk(-2, -2, 0.0, 0.0);
  if (k - 2 >= first) {
    vec2 s2 = texelFetch(surface_tex, at(k - 2), 0).xy;
    w.prev_id = int(s2.y);
    w.prev_z = s2.x;
  }
  if (k - 1 >= first) {
    vec2 s1 = texelFetch(surface_tex, at(k - 1), 0).xy;
    w.prev2_id = w.prev_id;
    w.prev2_z = w.prev_z;
    w.prev_id = int(s1.y);
    w.prev_z = s1.x;
  }
  return w;
}

void main() {
  g_vertical = blur.direction.y > 0.5;
  ivec2 lo = ivec2(frame.rect.xy), hi = ivec2(frame.rect.zw);  // hi exclusive
  g_line = int(gl_WorkGroupID.x) + (g_vertical ? lo.x : lo.y);
  if (g_line >= (g_vertical ? hi.x : hi.y)) return;  // the whole workgroup
  int first = g_vertical ? lo.y : lo.x, end = g_vertical ? hi.y : hi.x;
  int t = int(gl_LocalInvocationID.x);
  int chunk = (end - first + kPrefixThreads - 1) / kPrefixThreads;
  int k0 = min(first + t * chunk, end), k1 = min(k0 + chunk, end);

  // 1. This chunk's breaks and its sum since the last one.
  Walk w = walk_before(k0, first);
  vec3 tail = vec3(0.0);
  int last_start = -1;
  for (int k = k0; k < k1; ++k) {
    if (starts_run(w, texelFetch(surface_tex, at(k), 0).xy)) {
      tail = vec3(0.0);
      last_start = k;
    }
    tail += texelFetch(input_tex, at(k), 0).rgb;
  }
  chunk_tail[t] = tail;
  chunk_start[t] = last_start;
  barrier();

  // 2. The carries, in chunk order (kPrefixThreads steps in shared memory).
  if (t == 0) {
    vec3 sum = vec3(0.0);
    int start = first;
    for (int c = 0; c < kPrefixThreads; ++c) {
      carry_sum[c] = sum;
      carry_start[c] = start;
      if (chunk_start[c] >= 0) {
        sum = chunk_tail[c];
        start = chunk_start[c];
      } else {
        sum += chunk_tail[c];
      }
    }
  }
  barrier();

  // 3. The running sums from the carry.
  w = walk_before(k0, first);
  vec3 sum = carry_sum[t];
  int run_start = carry_start[t];
  for (int k = k0; k < k1; ++k) {
    ivec2 p = at(k);
    if (starts_run(w, texelFetch(surface_tex, p, 0).xy)) {
      sum = vec3(0.0);
      run_start = k;
    }
    sum += texelFetch(input_tex, p, 0).rgb;
    imageStore(prefix_img, p, vec4(sum, float(run_start)));
  }
}
