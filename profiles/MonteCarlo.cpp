#include "profiles/MonteCarlo.h"

#include "profiles/Fresnel.h"
#include "profiles/Random.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

namespace sss::profiles {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A weight this small can never show in a double-precision tally of order-1 values; a
// photon that reflects down to it ends (bias below 1e-250 per photon). Only walks with no
// scattering at all (sigma_s = 0) end this way: otherwise roulette ends them first.
constexpr double kNegligibleWeight = 1e-250;

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument(field + ": " + why);
}

void validate(const Coefficients& c, const MonteCarloOptions& o) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  if (o.photons == 0) fail("photons", "must be > 0");
  if (o.threads < 0) fail("threads", "must be >= 0 (0: all hardware threads)");
  if (!(o.thickness_mm > 0.0)) fail("thickness_mm", "must be > 0 mm (or infinity)");
  if (o.bin_edges_mm.size() == 1) fail("bin_edges_mm", "a single edge bounds no bin");
  for (std::size_t i = 0; i < o.bin_edges_mm.size(); ++i) {
    const double e = o.bin_edges_mm[i];
    if (!std::isfinite(e) || e < 0.0) fail("bin_edges_mm", "edges must be finite and >= 0");
    if (i > 0 && !(e > o.bin_edges_mm[i - 1]))
      fail("bin_edges_mm", "edges must be strictly ascending (edge " + std::to_string(i) + ")");
  }
  if (!(o.roulette_weight > 0.0 && o.roulette_weight < 1.0))
    fail("roulette_weight", "must lie in (0, 1)");
  if (!(o.roulette_survival > 0.0 && o.roulette_survival < 1.0))
    fail("roulette_survival", "must lie in (0, 1)");
  if (o.max_interactions_per_photon == 0) fail("max_interactions_per_photon", "must be > 0");
  if (o.max_scattering_order < 0) fail("max_scattering_order", "must be >= 0 (0: all)");
}

// Per-chunk sums of per-photon contributions. Bins [0, nb) are reflectance, [nb, 2nb)
// transmittance. Totals: 0 reflectance, 1 transmittance, 2 absorbed.
struct ChunkSums {
  std::vector<double> sum, sum_sq;
  double total[3] = {0, 0, 0};
  double total_sq[3] = {0, 0, 0};
  std::uint64_t events = 0;
  std::uint64_t truncated = 0;

  explicit ChunkSums(std::size_t slots) : sum(slots, 0.0), sum_sq(slots, 0.0) {}
  void add(const ChunkSums& o) {
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum[i] += o.sum[i];
      sum_sq[i] += o.sum_sq[i];
    }
    for (int k = 0; k < 3; ++k) {
      total[k] += o.total[k];
      total_sq[k] += o.total_sq[k];
    }
    events += o.events;
    truncated += o.truncated;
  }
};

// One worker's walker: the per-photon dense accumulator and its list of touched slots are
// allocated once and reused, so a photon allocates nothing.
class Walker {
 public:
  Walker(const Coefficients& c, const MonteCarloOptions& o)
      : c_(c), o_(o), nb_(o.bin_edges_mm.empty() ? 0 : o.bin_edges_mm.size() - 1),
        photon_(2 * nb_, 0.0) {
    touched_.reserve(2 * nb_);
  }

  void run_chunk(std::uint64_t chunk, std::uint64_t count, ChunkSums& out) {
    Xoshiro256ss rng(o_.seed, chunk);
    for (std::uint64_t p = 0; p < count; ++p) {
      double totals[3] = {0, 0, 0};
      walk(rng, totals, out);
      for (int k = 0; k < 3; ++k) {
        out.total[k] += totals[k];
        out.total_sq[k] += totals[k] * totals[k];
      }
      for (std::size_t slot : touched_) {
        const double x = photon_[slot];
        out.sum[slot] += x;
        out.sum_sq[slot] += x * x;
        photon_[slot] = 0.0;
      }
      touched_.clear();
    }
  }

 private:
  void tally(std::size_t face, double r, double w) {
    const auto& e = o_.bin_edges_mm;
    if (nb_ == 0 || w == 0.0 || r < e.front() || r >= e.back()) return;
    const auto bin = std::upper_bound(e.begin(), e.end(), r) - e.begin() - 1;
    const std::size_t slot = face * nb_ + static_cast<std::size_t>(bin);
    if (photon_[slot] == 0.0) touched_.push_back(slot);
    photon_[slot] += w;
  }

  // One photon. The current weight is w0 * exp(-sigma_a * len): `len` is the path walked
  // since w0 last changed, so the exponential is evaluated only at boundary hits and
  // roulette, not at every scattering event.
  void walk(Xoshiro256ss& rng, double totals[3], ChunkSums& out) {
    const double sa = c_.sigma_a, ss = c_.sigma_s, g = c_.g, d = o_.thickness_mm;
    const double inv_eta = 1.0 / c_.eta;
    double x = 0, y = 0, z = 0, ux = 0, uy = 0, uz = 1;
    double w0 = 1.0, len = 0.0;
    // The path length at which the weight falls below the roulette threshold.
    auto roulette_len = [&] {
      return w0 > o_.roulette_weight ? std::log(w0 / o_.roulette_weight) / sa : 0.0;
    };
    double len_roulette = roulette_len();
    int order = 0;
    for (std::uint64_t n = 0;; ++n) {
      if (n == o_.max_interactions_per_photon) {
        ++out.truncated;
        return;
      }
      const double s = ss > 0.0 ? -std::log(1.0 - rng.uniform()) / ss : kInf;
      double db = kInf;  // distance to the face ahead
      if (uz < 0.0) db = std::max(-z / uz, 0.0);
      else if (uz > 0.0) db = std::max((d - z) / uz, 0.0);
      if (s < db) {  // scattering event
        x += s * ux, y += s * uy, z += s * uz;
        len += s;
        if (o_.max_scattering_order > 0 && ++order > o_.max_scattering_order) return;
        ++out.events;
        if (len > len_roulette) {
          const double w = w0 * std::exp(-sa * len);
          totals[2] += w0 - w;
          len = 0.0;
          if (rng.uniform() >= o_.roulette_survival) return;
          w0 = w / o_.roulette_survival;
          len_roulette = roulette_len();
        }
        scatter(rng, g, ux, uy, uz);
        continue;
      }
      if (db == kInf) {  // no scattering and no face ahead: everything is absorbed
        totals[2] += w0;
        return;
      }
      x += db * ux, y += db * uy;
      const bool top = uz < 0.0;
      z = top ? 0.0 : d;
      const double w = w0 * std::exp(-sa * (len + db));
      totals[2] += w0 - w;
      const double fr = fresnel_dielectric(std::fabs(uz), inv_eta);
      const double escaped = w * (1.0 - fr);
      totals[top ? 0 : 1] += escaped;
      tally(top ? 0 : 1, std::sqrt(x * x + y * y), escaped);
      w0 = w * fr;
      len = 0.0;
      uz = -uz;
      if (w0 < kNegligibleWeight) {
        totals[2] += w0;  // (at most 1e-250) counted as absorbed so the balance closes
        return;
      }
      len_roulette = roulette_len();
    }
  }

  // New direction: cos θ from Henyey–Greenstein about the old direction, φ uniform, in
  // the orthonormal basis of Duff et al. 2017 ("Building an orthonormal basis,
  // revisited", JCGT 6(1)), which is accurate for every unit vector.
  static void scatter(Xoshiro256ss& rng, double g, double& ux, double& uy, double& uz) {
    const double ct = sample_hg_cos(g, rng.uniform());
    const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    double cp, sp;
    sample_azimuth(rng, cp, sp);
    const double sign = std::copysign(1.0, uz);
    const double a = -1.0 / (sign + uz);
    const double b = ux * uy * a;
    const double t1x = 1.0 + sign * ux * ux * a, t1y = sign * b, t1z = -sign * ux;
    const double t2x = b, t2y = sign + uy * uy * a, t2z = -uy;
    const double px = st * cp, py = st * sp;
    const double nx = px * t1x + py * t2x + ct * ux;
    const double ny = px * t1y + py * t2y + ct * uy;
    const double nz = px * t1z + py * t2z + ct * uz;
    // Renormalise so rounding cannot accumulate over thousands of events.
    const double inv = 1.0 / std::sqrt(nx * nx + ny * ny + nz * nz);
    ux = nx * inv, uy = ny * inv, uz = nz * inv;
  }

  const Coefficients& c_;
  const MonteCarloOptions& o_;
  std::size_t nb_;
  std::vector<double> photon_;
  std::vector<std::size_t> touched_;
};

// Mean and standard error from sums of per-photon contributions x over n photons.
void finish(double sum, double sum_sq, double n, double scale, double& mean, double& se) {
  mean = sum / n * scale;
  if (n < 2.0) {
    se = kInf;
    return;
  }
  const double m2 = std::max(0.0, sum_sq - sum * (sum / n));
  se = std::sqrt(m2 / (n * (n - 1.0))) * scale;
}

}  // namespace

MonteCarloResult run_monte_carlo(const Coefficients& c, const MonteCarloOptions& opt) {
  validate(c, opt);
  const auto start = std::chrono::steady_clock::now();
  const std::size_t nb = opt.bin_edges_mm.empty() ? 0 : opt.bin_edges_mm.size() - 1;
  const std::uint64_t chunks =
      (opt.photons + kMonteCarloChunkPhotons - 1) / kMonteCarloChunkPhotons;
  std::uint64_t threads = opt.threads > 0 ? static_cast<std::uint64_t>(opt.threads)
                                          : std::max(1u, std::thread::hardware_concurrency());
  threads = std::min(threads, chunks);

  // Chunks are claimed in any order but summed strictly in chunk order: a finished chunk
  // waits in `pending` until every earlier one has been added.
  ChunkSums total(2 * nb);
  std::map<std::uint64_t, ChunkSums> pending;
  std::uint64_t next_to_add = 0;
  std::atomic<std::uint64_t> next_chunk{0};
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::mutex mutex;

  auto worker = [&] {
    try {
      Walker walker(c, opt);
      for (;;) {
        const std::uint64_t k = next_chunk.fetch_add(1);
        if (k >= chunks || stop.load()) return;
        const std::uint64_t count =
            std::min(kMonteCarloChunkPhotons, opt.photons - k * kMonteCarloChunkPhotons);
        ChunkSums sums(2 * nb);
        walker.run_chunk(k, count, sums);
        std::lock_guard lock(mutex);
        pending.emplace(k, std::move(sums));
        for (auto it = pending.find(next_to_add); it != pending.end();
             it = pending.find(next_to_add)) {
          total.add(it->second);
          pending.erase(it);
          ++next_to_add;
          if (opt.progress) opt.progress(static_cast<double>(next_to_add) / chunks);
        }
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> pool;
  for (std::uint64_t t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);

  MonteCarloResult r;
  r.bin_edges_mm = opt.bin_edges_mm;
  r.photons = opt.photons;
  r.scattering_events = total.events;
  r.truncated_photons = total.truncated;
  const double n = static_cast<double>(opt.photons);
  MonteCarloTally* faces[2] = {&r.reflectance, &r.transmittance};
  for (std::size_t f = 0; f < 2; ++f) {
    MonteCarloTally& t = *faces[f];
    finish(total.total[f], total.total_sq[f], n, 1.0, t.total, t.total_stderr);
    t.value.resize(nb);
    t.stderr_.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const double r0 = opt.bin_edges_mm[b], r1 = opt.bin_edges_mm[b + 1];
      const double area = std::numbers::pi * (r1 * r1 - r0 * r0);
      finish(total.sum[f * nb + b], total.sum_sq[f * nb + b], n, 1.0 / area, t.value[b],
             t.stderr_[b]);
    }
  }
  finish(total.total[2], total.total_sq[2], n, 1.0, r.absorbed, r.absorbed_stderr);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<double> log_bin_edges(double lo, double hi, int count) {
  if (!(lo > 0.0 && hi > lo && std::isfinite(hi)))
    fail("log_bin_edges", "needs 0 < lo < hi, both finite");
  if (count < 1) fail("log_bin_edges", "needs count >= 1");
  std::vector<double> edges{0.0};
  const double step = std::log(hi / lo) / count;
  for (int i = 0; i < count; ++i) edges.push_back(lo * std::exp(step * i));
  edges.push_back(hi);
  return edges;
}

}  // namespace sss::profiles
