// The sampling loop that both per-pixel Monte Carlo renderers of the reference share (the
// random-walk ground truth, GroundTruth.h, and the probe diffusion reference,
// ProbeReference.h): passes of samples over a list of pixels, each pixel's running mean
// and variance of the mean (Welford), and, with a target error, passes that grow towards
// the sample count the measured noise says is needed.
//
// Reproducible: sample k of pixel i is whatever `sample(i, k, tls)` returns for it, and a
// pixel's samples are added in order by one thread, so the result depends on `sample`
// alone, not on the thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <glm/vec3.hpp>

#include "profiles/Medium.h"
#include "image/Image.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::reference {

// Welford's running mean and sum of squared deviations of a pixel's samples.
struct PixelAccumulator {
  glm::dvec3 mean{0.0}, m2{0.0};
  std::uint64_t n = 0;
  void add(const glm::dvec3& x) {
    ++n;
    const glm::dvec3 delta = x - mean;
    mean += delta / double(n);
    m2 += delta * (x - mean);
  }
  glm::dvec3 variance_of_mean() const { return n > 1 ? m2 / (double(n) * double(n - 1)) : glm::dvec3(0.0); }
};

// The sample-count options both renderers take: a fixed count, a target error, or both
// (the count then caps). `noun` names what one sample is ("samples", "probe batches").
// Throws std::invalid_argument naming the option.
inline void check_sample_counts(std::uint64_t spp, double target_error, const std::string& noun) {
  if (!(std::isfinite(target_error) && target_error >= 0.0 && target_error < 1.0))
    throw std::invalid_argument("target error: expected a relative standard error in (0, 1), got " +
                                message_number(target_error));
  if (spp == 0 && target_error == 0.0)
    throw std::invalid_argument("spp: give a number of " + noun + " per pixel >= 1, or a target error");
  if (target_error > 0.0 && spp == 1)
    throw std::invalid_argument("spp: a target error needs at least 2 " + noun + " per pixel to measure the noise");
}

// Writes each pixel's estimate, base + factor · mean, and its variance of the mean,
// factor² · var, into the images at the pixel's index (Plan: index, base, factor).
template <class Plan>
void write_pixel_estimates(const std::vector<Plan>& plans, const std::vector<PixelAccumulator>& acc,
                           image::Image& hdr, image::Image& variance) {
  for (std::size_t i = 0; i < plans.size(); ++i) {
    const Plan& p = plans[i];
    float* px = &hdr.rgba[std::size_t(p.index) * 4];
    float* pv = &variance.rgba[std::size_t(p.index) * 4];
    const glm::dvec3 mean = p.base + p.factor * acc[i].mean;
    const glm::dvec3 var = p.factor * p.factor * acc[i].variance_of_mean();
    for (int c = 0; c < 3; ++c) {
      px[c] = float(mean[c]);
      pv[c] = float(var[c]);
    }
  }
}

struct PassSettings {
  std::uint64_t spp = 0;      // samples per pixel; with a target error the most a pixel gets (0: no limit)
  double target_error = 0.0;  // > 0: stop when the frame's relative standard error is at most this
  const char* stage = "walk"; // progress stage of the sampling passes ("noise" for a first measuring pass)
};

struct PassResult {
  std::uint64_t spp = 0;  // samples every pixel got
  int passes = 0;
  double relative_standard_error = 0.0;  // as `error` returned after the last pass
};

// The pixels to sample, planned row by row in parallel: `row(y, plans)` appends row y's
// pixels that need samples (and may write what is deterministic about the others). Rows
// the tile does not own (Tile: anything with owns_row(y), TileMerge.h's TileSpec) are
// skipped, as is every row once `cancelled()`. The plans come back in pixel order.
template <class Plan, class Tile, class Cancelled, class Row>
std::vector<Plan> plan_rows(std::uint32_t height, const Tile& tile, tbb::task_arena& arena, const Cancelled& cancelled,
                            const Row& row) {
  std::vector<std::vector<Plan>> rows(height);
  arena.execute([&] {
    tbb::parallel_for(std::uint32_t(0), height, [&](std::uint32_t y) {
      if (!tile.owns_row(y) || cancelled()) return;
      row(y, rows[y]);
    });
  });
  std::vector<Plan> plans;
  for (std::vector<Plan>& r : rows)
    for (const Plan& p : r) plans.push_back(p);
  return plans;
}

// Samples pixels 0..count-1. `sample(i, k, tls)` returns sample k of pixel i (Tls: per
// thread scratch or statistics); after each pass `error(acc)` writes the images from the
// accumulators and returns the frame's relative standard error. Returns with
// `cancelled()` true at the first check after it became so (the caller throws).
template <class Tls, class Sample, class Error>
PassResult run_sample_passes(std::size_t count, const PassSettings& settings, tbb::task_arena& arena,
                             tbb::enumerable_thread_specific<Tls>& tls, std::vector<PixelAccumulator>& acc,
                             const Sample& sample, const Error& error, const std::function<bool()>& cancelled,
                             const std::function<void(const char*, double)>& report) {
  PassResult result;
  acc.assign(count, PixelAccumulator{});
  if (count == 0) return result;
  const std::uint64_t cap = settings.spp;
  const bool targeted = settings.target_error > 0.0;
  std::uint64_t done = 0;
  std::uint64_t next = targeted ? (cap > 0 ? std::min<std::uint64_t>(cap, 16) : 16) : cap;
  std::atomic<std::uint64_t> samples_done{0};
  const double per_sample = 1.0 / double(count);
  for (;;) {
    const std::uint64_t from = done, to = next;
    const double planned = double(to);  // samples per pixel this run is heading for
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4), [&](const tbb::blocked_range<std::size_t>& r) {
        Tls& local = tls.local();
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          if (cancelled()) return;
          for (std::uint64_t k = from; k < to; ++k) {
            if ((k & 255u) == 255u && cancelled()) return;
            acc[i].add(sample(i, k, local));
          }
          const std::uint64_t n = samples_done.fetch_add(to - from) + (to - from);
          // With a target error the first pass measures the noise; each later one heads
          // for the samples that noise says are needed.
          report(targeted && from == 0 ? "noise" : settings.stage, double(n) * per_sample / planned);
        }
      });
    });
    if (cancelled()) return result;
    done = to;
    ++result.passes;
    result.relative_standard_error = error(acc);
    if (!targeted || result.relative_standard_error <= settings.target_error || (cap > 0 && done >= cap)) break;
    const double e = result.relative_standard_error / settings.target_error;
    std::uint64_t want = std::uint64_t(std::ceil(double(done) * e * e * 1.05));
    want = std::clamp<std::uint64_t>(want, done + 1, 4 * done);
    next = cap > 0 ? std::min(cap, want) : want;
  }
  result.spp = done;
  return result;
}

}  // namespace sss::reference
