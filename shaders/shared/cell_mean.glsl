// A 1D blur's tap as the mean of its input over the tap's cell (issue 20, "separable
// streaks"): two of sss_prefix.comp's running sums, one at each end of the cell, and the
// input texels there. For sss_separable.comp (Jimenez's cells); any 1D blur whose taps
// stand for intervals can use it. Not shared with C++.
#ifndef SSS_SHADERS_CELL_MEAN_GLSL
#define SSS_SHADERS_CELL_MEAN_GLSL

// Needs: blur (BlurPush), input_tex and prefix_tex (sampler2D, texelFetch).

// Along the pass's line: a pixel's coordinate (the prefix pass's run starts are in it).
float line_coord(ivec2 q) { return float(blur.direction.y > 0.5 ? q.y : q.x); }

// A cell boundary c pixels from p along the line, in the pixel m = round(c) whose
// footprint [m - 1/2, m + 1/2) holds it: the input integrated over the run from the run's
// start to c (the input is constant over each pixel, so the inclusive sum at m less the
// part of m's value beyond c), m's input texel, and the run's first pixel.
struct CellEdge {
  float c;
  int m;
  ivec2 q;      // the pixel m, clamped to the rect
  bool inside;  // m lies in the rect
  vec3 sum;
  vec4 texel;
  float run_start;
};

// lo, hi: the rect's first and last pixels (inclusive).
CellEdge cell_edge(ivec2 p, ivec2 step, ivec2 lo, ivec2 hi, float c) {
  CellEdge e;
  e.c = c;
  e.m = int(floor(c + 0.5));
  ivec2 q = p + step * e.m;
  e.inside = all(greaterThanEqual(q, lo)) && all(lessThanEqual(q, hi));
  e.q = clamp(q, lo, hi);
  vec4 prefix = texelFetch(prefix_tex, e.q, 0);
  e.texel = texelFetch(input_tex, e.q, 0);
  e.sum = prefix.rgb - e.texel.rgb * (float(e.m) + 0.5 - c);
  e.run_start = prefix.a;
  return e;
}

// Whether the mean over [lower.c, upper.c] can stand for the tap: both ends in the rect,
// the cell at least a pixel wide (narrower cells have no staircase), one run throughout.
bool one_run(CellEdge lower, CellEdge upper) {
  return lower.inside && upper.inside && upper.c - lower.c >= 1.0 &&
         upper.run_start <= line_coord(lower.q);
}

vec3 cell_mean(CellEdge lower, CellEdge upper) { return (upper.sum - lower.sum) / (upper.c - lower.c); }

#endif
