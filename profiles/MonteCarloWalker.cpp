#include "profiles/MonteCarloWalker.h"

#include "profiles/Fresnel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sss::profiles::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A weight this small can never show in a double-precision tally of order-1 values; a
// photon that reflects down to it ends (bias below 1e-250 per photon). Only walks with no
// scattering at all (sigma_s = 0) end this way: otherwise roulette ends them first.
constexpr double kNegligibleWeight = 1e-250;

}  // namespace

Walker::Walker(const std::vector<Layer>& layers, const MonteCarloOptions& o)
    : layers_(layers), o_(o), bottom_(layers.size()), scatters_(false),
      nb_(o.bin_edges_mm.empty() ? 0 : o.bin_edges_mm.size() - 1),
      nc_(static_cast<std::size_t>(o.exit_cosine_bins)), photon_(2 * nb_ + nc_, 0.0) {
  touched_.reserve(2 * nb_ + nc_);
  // Faces at the running sums of the thicknesses: one layer of thickness d has its bottom
  // at 0 + d = d exactly, as the single-medium walk had it.
  double z = 0.0;
  for (std::size_t k = 0; k < layers.size(); ++k) {
    z += layers[k].thickness_mm;
    bottom_[k] = z;
    scatters_ = scatters_ || layers[k].c.sigma_s > 0.0;
  }
}

void Walker::run_chunk(std::uint64_t chunk, std::uint64_t count, ChunkSums& out) {
  Xoshiro256ss rng(o_.seed, chunk);
  for (std::uint64_t p = 0; p < count; ++p) {
    double totals[kChunkTotals] = {0, 0, 0, 0};
    walk(rng, totals, out);
    for (int k = 0; k < kChunkTotals; ++k) {
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

void Walker::tally(std::size_t face, double r, double w) {
  const auto& e = o_.bin_edges_mm;
  if (nb_ == 0 || w == 0.0 || r < e.front() || r >= e.back()) return;
  const auto bin = std::upper_bound(e.begin(), e.end(), r) - e.begin() - 1;
  add(face * nb_ + static_cast<std::size_t>(bin), w);
}

void Walker::tally_exit_cosine(double cos_inside, double w) {
  if (nc_ == 0 || w == 0.0) return;
  // Snell: sin θo = η sin θi; the escaping part never exceeds the critical angle.
  const double eta = layers_[0].c.eta;  // every layer's (index-matched stack)
  const double sin2_o = eta * eta * (1.0 - cos_inside * cos_inside);
  const double cos_o = std::sqrt(std::max(0.0, 1.0 - sin2_o));
  const std::size_t k = std::min(nc_ - 1, static_cast<std::size_t>(cos_o * static_cast<double>(nc_)));
  add(2 * nb_ + k, w);
}

void Walker::add(std::size_t slot, double w) {
  if (photon_[slot] == 0.0) touched_.push_back(slot);
  photon_[slot] += w;
}

// One photon. The current weight is w0 * exp(-sigma_a * len), with the sigma_a of the
// layer the photon is in: `len` is the path walked in that layer since w0 last changed, so
// the exponential is evaluated only at boundary hits, interface crossings and roulette,
// not at every scattering event. Crossing an (index-matched) interface between layers
// folds the decay into w0, so `len` never spans two layers.
//
// A stack of one layer runs exactly the single-medium walk: the optical depth is drawn as
// tau = -log(1 - u) and s = tau / sigma_s, the same operations as the former
// s = -log(1 - u) / sigma_s, the top face's distance -(z - 0) / uz is -z / uz, and the
// crossing branch never runs. run_monte_carlo is therefore bit for bit what it was.
void Walker::walk(Xoshiro256ss& rng, double totals[kChunkTotals], ChunkSums& out) {
  const std::size_t last = layers_.size() - 1;
  const double inv_eta = 1.0 / layers_[0].c.eta;
  // The layer the photon is in, its coefficients and faces.
  std::size_t k = 0;
  double sa = 0, ss = 0, g = 0, top = 0, bottom = 0;
  auto enter = [&](std::size_t layer) {
    k = layer;
    const Coefficients& c = layers_[k].c;
    sa = c.sigma_a, ss = c.sigma_s, g = c.g;
    top = k == 0 ? 0.0 : bottom_[k - 1];
    bottom = bottom_[k];
  };
  enter(0);
  // The refracted beam: sin θt = sin θi / η in the x-z plane (straight down at normal
  // incidence).
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - o_.incidence_cos * o_.incidence_cos)) * inv_eta;
  double x = 0, y = 0, z = 0, ux = sin_t, uy = 0, uz = std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t));
  double w0 = 1.0, len = 0.0;
  // The path length (in the current layer) at which the weight falls below the roulette
  // threshold.
  auto roulette_len = [&] {
    return w0 > o_.roulette_weight ? std::log(w0 / o_.roulette_weight) / sa : 0.0;
  };
  double len_roulette = roulette_len();
  int order = 0;  // scattering events so far
  for (std::uint64_t n = 0;; ++n) {
    if (n == o_.max_interactions_per_photon) {
      ++out.truncated;
      return;
    }
    // The optical depth (in scattering) of this flight; without scattering anywhere no
    // random number is drawn and the walk is deterministic.
    double tau = scatters_ ? -std::log(1.0 - rng.uniform()) : kInf;
    double s, db;  // distance to the scattering event and to the face ahead, in this layer
    for (;;) {
      s = ss > 0.0 ? tau / ss : kInf;  // sigma_s = 0: the flight crosses the layer
      db = kInf;
      if (uz < 0.0) db = std::max(-(z - top) / uz, 0.0);
      else if (uz > 0.0) db = std::max((bottom - z) / uz, 0.0);
      if (s < db || db == kInf || (uz < 0.0 ? k == 0 : k == last)) break;
      // An interface to the next layer comes first: cross it unchanged in direction (the
      // layers share eta), and carry the depth not yet spent on to the next layer. The
      // clamp only absorbs rounding (s >= db means tau >= sigma_s db up to it).
      const bool up = uz < 0.0;
      x += db * ux, y += db * uy;
      z = up ? top : bottom;
      const double w = w0 * std::exp(-sa * (len + db));
      totals[2] += w0 - w;
      w0 = w;
      len = 0.0;
      if (ss > 0.0) tau = std::max(0.0, tau - ss * db);
      enter(up ? k - 1 : k + 1);
      len_roulette = roulette_len();
    }
    if (s < db) {  // scattering event
      x += s * ux, y += s * uy, z += s * uz;
      len += s;
      ++order;
      if (o_.max_scattering_order > 0 && order > o_.max_scattering_order) return;
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
    // An outer face: the top of layer 0 or the bottom of the last layer.
    x += db * ux, y += db * uy;
    const bool top_face = uz < 0.0;
    z = top_face ? 0.0 : bottom;
    const double w = w0 * std::exp(-sa * (len + db));
    totals[2] += w0 - w;
    const double fr = fresnel_dielectric(std::fabs(uz), inv_eta);
    const double escaped = w * (1.0 - fr);
    if (order >= o_.min_scattering_order) {
      totals[top_face ? 0 : 1] += escaped;
      tally(top_face ? 0 : 1, std::sqrt(x * x + y * y), escaped);
      if (top_face) tally_exit_cosine(std::fabs(uz), escaped);
    } else {
      totals[3] += escaped;  // left out (MonteCarloOptions::min_scattering_order)
    }
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
void Walker::scatter(Xoshiro256ss& rng, double g, double& ux, double& uy, double& uz) {
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

}  // namespace sss::profiles::detail
