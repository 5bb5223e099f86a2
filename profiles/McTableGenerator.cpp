// generate_mc_table: one set of random walks fills every (η, α') node of the mc-table.
//
// The medium is in optical units (σt' = 1) with isotropic scattering at albedo α'
// (similarity). Two observations make one walk serve the whole table:
//
// 1. Albedo scaling ("implicit capture" with σt flights). Flight lengths are sampled with
//    σt = 1, which does not depend on α', and at each scattering event the weight is
//    multiplied by α' instead of ending the photon with probability 1 - α'. A path with n
//    scattering events then carries α'^n for every α' at once: the path's geometry is
//    shared and only the weight depends on the albedo. This is the Monte Carlo scaling
//    idea of Graaff et al. 1993 (Applied Optics 32(4):426) and Kienle & Patterson 1996
//    (Phys. Med. Biol. 41:2221), who reuse one walk set for every absorption coefficient;
//    in optical units it is exact for every α', not an approximation, and it preserves
//    the similarity scaling because the walk is already in reduced units.
// 2. Fresnel splitting. At the surface a fraction 1 - F(μ, η) of the weight leaves and is
//    tallied, and the walk always reflects carrying F(μ, η). The reflected direction does
//    not depend on η, so the geometry is shared by every η too; each η keeps its own
//    weight, the product of its Fresnel reflectances along the path. At normal incidence
//    the refracted beam goes straight down for every η, so the entry is shared as well.
//
// An exit after n scattering events with η-weight w_η adds w_η α'^n to node (η, α').
// Both steps are unbiased for every node: they change what is sampled, not its mean.
//
// The once-scattered part (format version 2, McTable.h). The entering beam goes straight
// down, so an exit with n = 1 is the walk's first exit, with w_η = 1 - F(μ, η) (times the
// roulette's 1/survival if it fired at the first event, which only a table whose largest
// albedo is below the roulette weight's reach can see): it adds w_η α' to node (η, α'),
// and w_η alone is tallied per η as q, the once-scattered flux per unit albedo. The
// reflected rest goes down and leaves only after scattering again (n >= 2). So every
// node's flux is exactly α' q + (its exits with n >= 2), in the same walks.
//
// The walk ends by Russian roulette on its largest weight over every node, max_η w_η ·
// α'max^n (relative to 1 at entry): below `roulette_weight` it survives with probability
// `roulette_survival`, its weights divided by it. One decision for all nodes scales them
// all by the same factor, so every node stays unbiased (the weights of the smaller
// albedos are only ever smaller than that of the largest).
//
// Standard errors are batch means: photons are processed in batches ("chunks") of
// chunk_photons walks, each on its own RNG stream (seed, chunk), and the spread of the
// batch means gives the error of their mean. Batches are reduced strictly in order, so
// the result is the same bit for bit for any thread count. A walk allocates nothing:
// each worker owns its accumulators for the life of the run.
#include "profiles/McTable.h"

#include "profiles/Fresnel.h"
#include "profiles/Medium.h"
#include "profiles/OrderedChunks.h"
#include "profiles/Random.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace sss::profiles {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& why) {
  throw std::invalid_argument(field + ": " + why);
}

void check_ascending(const std::vector<double>& v, const char* field, double lo, double hi,
                     bool lo_open, bool hi_open) {
  if (v.empty()) fail(field, "needs at least one value");
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double x = v[i];
    const bool below = lo_open ? !(x > lo) : !(x >= lo);
    const bool above = hi_open ? !(x < hi) : !(x <= hi);
    if (!std::isfinite(x) || below || above)
      fail(field, "value " + std::to_string(i) + " (" + message_number(x) + ") must lie in " +
                      (lo_open ? "(" : "[") + message_number(lo) + ", " + message_number(hi) +
                      (hi_open ? ")" : "]"));
    if (i > 0 && !(x > v[i - 1]))
      fail(field, "values must be strictly ascending (value " + std::to_string(i) + ")");
  }
}

void validate(const McTableOptions& o) {
  check_ascending(o.eta, "eta", kEtaMin, kEtaMax, false, false);
  // Up to 1 - 1e-6: the walks end by roulette once α'max^n is small, after ~ln(20)/(1-α'max)
  // scattering events (3e6 at this bound; at 1 - 1e-12 a walk would practically never end).
  check_ascending(o.albedo, "albedo", 0.0, 1.0 - 1e-6, true, false);
  if (o.r_edges.size() < 2) fail("r_edges", "needs at least two edges (one annulus)");
  if (o.r_edges.front() != 0.0) fail("r_edges", "the first edge must be 0");
  check_ascending({o.r_edges.begin() + 1, o.r_edges.end()}, "r_edges", 0.0,
                  1e15, true, false);
  // What the file format can hold (parse_mc_table's limits).
  if (o.eta.size() > 1024) fail("eta", "at most 1024 values");
  if (o.albedo.size() > 4096) fail("albedo", "at most 4096 values");
  if (o.r_edges.size() > 4096) fail("r_edges", "at most 4096 edges");
  if (o.chunk_photons == 0) fail("chunk_photons", "must be > 0");
  if (o.photons == 0 || o.photons % o.chunk_photons != 0 || o.photons / o.chunk_photons < 2)
    fail("photons", "must be a multiple of chunk_photons (" + std::to_string(o.chunk_photons) +
                        ") and at least two chunks, got " + std::to_string(o.photons));
  if (o.threads < 0) fail("threads", "must be >= 0 (0: every hardware thread)");
  if (!(o.roulette_weight > 0.0 && o.roulette_weight < 1.0))
    fail("roulette_weight", "must lie in (0, 1)");
  if (!(o.roulette_survival > 0.0 && o.roulette_survival < 1.0))
    fail("roulette_survival", "must lie in (0, 1)");
  if (!(o.g > -1.0 && o.g < 1.0)) fail("g", "must lie in (-1, 1), got " + message_number(o.g));
}

// The sums of one chunk. Layout [bin][eta][albedo] so that an exit adds to one contiguous
// block of n_eta * n_albedo values.
struct Chunk {
  std::vector<double> flux;         // [bin][eta][albedo]
  std::vector<double> total;        // [eta][albedo]
  // Exits with n = 1: per unit albedo [bin][eta] and [eta] for g = 0; for g != 0 the
  // once-scattered flux itself, [bin][eta][albedo] and [eta][albedo] (see below).
  std::vector<double> single_flux;
  std::vector<double> single_total;
};

class TableWalker {
 public:
  explicit TableWalker(const McTableOptions& o)
      : o_(o), ne_(o.eta.size()), na_(o.albedo.size()), nb_(o.r_edges.size() - 1),
        aniso_(o.g != 0.0), inv_eta_(ne_), ln_albedo_(na_), power_(na_), weight_(ne_),
        radial_scale_(na_, 1.0), bin_(na_, 0) {
    for (std::size_t e = 0; e < ne_; ++e) inv_eta_[e] = 1.0 / o.eta[e];
    for (std::size_t a = 0; a < na_; ++a) {
      // g != 0: the walk is in real units (σt = 1) at the real albedo α of the node's
      // reduced albedo α' (see the header comment), and r scales to reduced units by σt'.
      const double alpha = real_albedo(o.albedo[a], o.g);
      ln_albedo_[a] = std::log(alpha);
      radial_scale_[a] = 1.0 - alpha * o.g;
    }
    ln_albedo_max_ = ln_albedo_.back();
    ln_roulette_ = std::log(o.roulette_weight);
  }

  void run(std::uint64_t chunk, Chunk& out) {
    out.flux.assign(nb_ * ne_ * na_, 0.0);
    out.total.assign(ne_ * na_, 0.0);
    out.single_flux.assign(nb_ * ne_ * (aniso_ ? na_ : 1), 0.0);
    out.single_total.assign(ne_ * (aniso_ ? na_ : 1), 0.0);
    Xoshiro256ss rng(o_.seed, chunk);
    for (std::uint64_t p = 0; p < o_.chunk_photons; ++p) walk(rng, out);
  }

 private:
  // The scattering count above which max_η w_η · α'max^n falls below the roulette weight.
  double roulette_count(double w_max) const {
    return (std::log(w_max) - ln_roulette_) / -ln_albedo_max_;
  }

  void walk(Xoshiro256ss& rng, Chunk& out) {
    std::fill(weight_.begin(), weight_.end(), 1.0);
    double w_max = 1.0;
    double x = 0, y = 0, z = 0, ux = 0, uy = 0, uz = 1;
    std::uint64_t n = 0;
    double n_roulette = roulette_count(w_max);
    for (;;) {
      const double s = -std::log(1.0 - rng.uniform());  // σt = 1
      const double db = uz < 0.0 ? std::max(-z / uz, 0.0) : kInf;
      if (s < db) {  // a scattering event
        x += s * ux, y += s * uy, z += s * uz;
        ++n;
        if (static_cast<double>(n) > n_roulette) {
          if (rng.uniform() >= o_.roulette_survival) return;
          for (double& w : weight_) w /= o_.roulette_survival;
          w_max /= o_.roulette_survival;
          n_roulette = roulette_count(w_max);
        }
        if (aniso_) {
          scatter_hg(rng, ux, uy, uz);
          continue;
        }
        // Isotropic: cos θ uniform in [-1, 1], φ uniform.
        uz = 2.0 * rng.uniform() - 1.0;
        const double st = std::sqrt(std::max(0.0, 1.0 - uz * uz));
        double cp, sp;
        sample_azimuth(rng, cp, sp);
        ux = st * cp, uy = st * sp;
        continue;
      }
      // At the surface: every η leaves its share and reflects the rest.
      x += db * ux, y += db * uy, z = 0.0;
      const double r = std::sqrt(x * x + y * y);
      const double mu = -uz;
      // α'^n for the albedos whose share is not negligible: below e^-50 (2e-22) relative
      // to its first-order share α' no tally can show it. Albedos ascend, so these are
      // the nodes from a0 up; long walks (large n) touch only the brightest nodes.
      const double dn = static_cast<double>(n);
      std::size_t a0 = na_;
      while (a0 > 0 && (dn - 1.0) * ln_albedo_[a0 - 1] > -50.0) --a0;
      for (std::size_t a = a0; a < na_; ++a) power_[a] = std::exp(dn * ln_albedo_[a]);
      const bool once = n == 1;
      // Where the exit lands: one annulus for every albedo (g = 0), or one per albedo.
      double* bin_block = nullptr;
      double* single_block = nullptr;
      if (aniso_) {
        scaled_bins(r, a0);
      } else if (r < o_.r_edges.back()) {
        const auto b = static_cast<std::size_t>(
            std::upper_bound(o_.r_edges.begin(), o_.r_edges.end(), r) - o_.r_edges.begin() - 1);
        bin_block = out.flux.data() + b * ne_ * na_;
        single_block = out.single_flux.data() + b * ne_;
      }
      w_max = 0.0;
      for (std::size_t e = 0; e < ne_; ++e) {
        const double w = weight_[e];
        if (w == 0.0) continue;
        const double fr = fresnel_dielectric(mu, inv_eta_[e]);
        const double escaped = w * (1.0 - fr);
        weight_[e] = w * fr;
        w_max = std::max(w_max, weight_[e]);
        if (aniso_) {
          tally_scaled(e, escaped, a0, once, out);
          continue;
        }
        double* tot = out.total.data() + e * na_;
        for (std::size_t a = a0; a < na_; ++a) tot[a] += escaped * power_[a];
        if (bin_block) {
          double* f = bin_block + e * na_;
          for (std::size_t a = a0; a < na_; ++a) f[a] += escaped * power_[a];
        }
        if (once) {
          out.single_total[e] += escaped;
          if (single_block) single_block[e] += escaped;
        }
      }
      if (w_max < kNegligible) return;  // e.g. a table of η = 1 alone: all has left
      n_roulette = roulette_count(w_max);
      uz = -uz;
    }
  }

  // g != 0: the exit at real radius r lands in node a's annulus of r·σt'(a), a different
  // one per albedo: bin_[a] for the albedos from a0 up (nb_: past the last edge).
  void scaled_bins(double r, std::size_t a0) {
    const double last = o_.r_edges.back();
    for (std::size_t a = a0; a < na_; ++a) {
      const double rs = r * radial_scale_[a];
      bin_[a] = rs < last ? static_cast<std::size_t>(
                                std::upper_bound(o_.r_edges.begin(), o_.r_edges.end(), rs) -
                                o_.r_edges.begin() - 1)
                          : nb_;
    }
  }

  // g != 0: η node e's escaped weight into every albedo's total and annulus (power_ holds
  // α^n from a0 up); the once-scattered flux per node.
  void tally_scaled(std::size_t e, double escaped, std::size_t a0, bool once, Chunk& out) {
    const std::size_t block = ne_ * na_;
    double* tot = out.total.data() + e * na_;
    double* stot = out.single_total.data() + e * na_;
    for (std::size_t a = a0; a < na_; ++a) {
      const double v = escaped * power_[a];
      tot[a] += v;
      if (once) stot[a] += v;
      if (bin_[a] == nb_) continue;
      const std::size_t k = bin_[a] * block + e * na_ + a;
      out.flux[k] += v;
      if (once) out.single_flux[k] += v;
    }
  }

  // Henyey-Greenstein scattering of the unit direction u: cos θ by sample_hg_cos, φ
  // uniform, turned into the frame of u with the rotation formulas of Wang, Jacques &
  // Zheng's MCML (Comput. Methods Programs Biomed. 47:131, 1995, eq. 3.24-3.25), written
  // here apart from the analog walk's own frame construction (MonteCarloWalker.cpp) so
  // that the table and the walk it is checked against do not share this code.
  void scatter_hg(Xoshiro256ss& rng, double& ux, double& uy, double& uz) const {
    const double ct = sample_hg_cos(o_.g, rng.uniform());
    const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
    double cp, sp;
    sample_azimuth(rng, cp, sp);
    double nx, ny, nz;
    if (std::fabs(uz) > 0.99999) {
      nx = st * cp, ny = st * sp, nz = uz > 0.0 ? ct : -ct;
    } else {
      const double s = std::sqrt(1.0 - uz * uz);
      nx = st * (ux * uz * cp - uy * sp) / s + ux * ct;
      ny = st * (uy * uz * cp + ux * sp) / s + uy * ct;
      nz = -st * cp * s + uz * ct;
    }
    const double inv = 1.0 / std::sqrt(nx * nx + ny * ny + nz * nz);
    ux = nx * inv, uy = ny * inv, uz = nz * inv;
  }

  static constexpr double kInf = std::numeric_limits<double>::infinity();
  // Weights this small cannot show in tallies of order 1e-12 and above.
  static constexpr double kNegligible = 1e-250;

  const McTableOptions& o_;
  std::size_t ne_, na_, nb_;
  bool aniso_;
  std::vector<double> inv_eta_, ln_albedo_, power_, weight_, radial_scale_;
  std::vector<std::size_t> bin_;
  double ln_albedo_max_ = 0.0, ln_roulette_ = 0.0;
};

}  // namespace

McTableOptions shipped_mc_table_options() {
  McTableOptions o;
  // η: 1.0 to 2.5 in steps of 0.05, the whole range the library accepts (kEtaMin..kEtaMax;
  // skin 1.4, milk 1.35, marble and jade 1.5-1.6). The walks are shared by every η, but
  // a high η keeps them alive longer (its internal reflectance is high): on this
  // machine 54 µs per walk up to 1.6, 155 µs up to 2.5.
  for (int i = 0; i <= 30; ++i) o.eta.push_back((100.0 + 5.0 * i) / 100.0);
  // α': 64 nodes uniform in u = √(1 - α') from u(0.9999) = 0.01 to u(0.01): the total
  // reflectance is close to linear in u near α' = 1 (1 - H(1) u at η = 1) and the
  // diffusion tail decays as exp(-√3 u r), so equal steps in u are equal steps in shape.
  // That puts 20 nodes above α' = 0.9 and 6 above 0.99.
  constexpr int kAlbedos = 64;
  const double u_lo = 0.01, u_hi = std::sqrt(1.0 - 0.01);
  for (int i = kAlbedos - 1; i >= 0; --i) {
    const double u = u_lo + (u_hi - u_lo) * i / (kAlbedos - 1);
    o.albedo.push_back(i == 0 ? 0.9999 : i == kAlbedos - 1 ? 0.01 : 1.0 - u * u);
  }
  // r: the disc [0, 1e-3) then 16 annuli per decade out to 1024 mean free paths; at
  // α' = 0.9999 the diffusion tail exp(-√3 u r) is e^-17.7 there.
  o.r_edges.push_back(0.0);
  constexpr int kPerDecade = 16, kDecades = 6;
  for (int i = 0; i <= kPerDecade * kDecades; ++i)
    o.r_edges.push_back(1e-3 * std::pow(10.0, static_cast<double>(i) / kPerDecade));
  o.r_edges.push_back(1024.0);
  o.photons = 1u << 22;
  o.seed = 1;
  o.chunk_photons = 4096;
  // Roulette at 5% of the entry weight: measured on 2^16 walks (η to 1.6), 3.5x the
  // efficiency (1 / (time × variance) of the total reflectance) of 1e-4 at α' = 0.86 and
  // 2.3x at α' = 0.9999, with the same per-annulus errors within their noise.
  o.roulette_weight = 0.05;
  o.roulette_survival = 0.1;
  return o;
}

const std::vector<double>& shipped_mc_table_g_values() {
  // Nearly uniform in ln(1 - g) (0, -0.36, -0.92, -1.61, -2.30, -3.00 with the isotropic
  // table at g = 0): the near-source shape changes with the number of real scattering
  // events per reduced mean free path, 1/(1 - g), and the lookup interpolates in ln(1 - g).
  static const std::vector<double> g = {0.3, 0.6, 0.8, 0.9, 0.95};
  return g;
}

McTableOptions shipped_mc_table_g_options(double g) {
  McTableOptions o = shipped_mc_table_options();
  o.g = g;
  // η: 1.0 to 2.5 in steps of 0.1 (16 nodes, half the isotropic table's density).
  o.eta.clear();
  for (int i = 0; i <= 15; ++i) o.eta.push_back((10.0 + i) / 10.0);
  // α': 32 nodes uniform in u = √(1 - α') over the isotropic table's range.
  constexpr int kAlbedos = 32;
  const double u_lo = 0.01, u_hi = std::sqrt(1.0 - 0.01);
  o.albedo.clear();
  for (int i = kAlbedos - 1; i >= 0; --i) {
    const double u = u_lo + (u_hi - u_lo) * i / (kAlbedos - 1);
    o.albedo.push_back(i == 0 ? 0.9999 : i == kAlbedos - 1 ? 0.01 : 1.0 - u * u);
  }
  // 2^18 walks (a sixteenth of the isotropic table's): a walk at g costs about 1/(1 - g)
  // times an isotropic one in scattering events (20x at g = 0.95), and the layers' goal,
  // 3% RMS in R(r), allows ~4x the isotropic table's noise.
  o.photons = 1u << 18;
  return o;
}

namespace {

// Running sums over chunks of the chunk sums and of their squares, in chunk order
// (OrderedChunks.h: the result does not depend on the thread count).
struct ChunkSums {
  std::size_t na, per_node;  // albedo nodes; once-scattered values per (bin, eta): 1 or na
  std::vector<double> flux_sum, flux_sq, total_sum, total_sq;
  // g = 0: once-scattered per unit albedo, [bin][eta] and [eta]; g != 0: per node.
  std::vector<double> single_flux_sum, single_flux_sq, single_total_sum, single_total_sq;
  // The multiply-scattered part of each chunk, d = S - α' S1 (S a chunk's sum at a node,
  // S1 its once-scattered sum per unit albedo): sums and squares of d, for its own
  // batch-means error (the two parts are correlated; see McTable.h).
  std::vector<double> multiple_flux_sum, multiple_flux_sq, multiple_total_sum, multiple_total_sq;

  ChunkSums(std::size_t ne, std::size_t n_albedo, std::size_t nb, std::size_t once_per_node)
      : na(n_albedo),
        per_node(once_per_node),
        flux_sum(nb * ne * na, 0.0),
        flux_sq(nb * ne * na, 0.0),
        total_sum(ne * na, 0.0),
        total_sq(ne * na, 0.0),
        single_flux_sum(nb * ne * per_node, 0.0),
        single_flux_sq(nb * ne * per_node, 0.0),
        single_total_sum(ne * per_node, 0.0),
        single_total_sq(ne * per_node, 0.0),
        multiple_flux_sum(nb * ne * na, 0.0),
        multiple_flux_sq(nb * ne * na, 0.0),
        multiple_total_sum(ne * na, 0.0),
        multiple_total_sq(ne * na, 0.0) {}

  static void add(std::vector<double>& sum, std::vector<double>& sq, const std::vector<double>& v) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      sum[i] += v[i];
      sq[i] += v[i] * v[i];
    }
  }
  // v: [block][eta][albedo], once: [block][eta] (g = 0: per unit albedo) or the same
  // layout as v (g != 0: the once-scattered flux itself).
  void add_multiple(std::vector<double>& sum, std::vector<double>& sq, const std::vector<double>& v,
                    const std::vector<double>& once, const std::vector<double>& albedo) const {
    if (per_node > 1) {
      for (std::size_t k = 0; k < v.size(); ++k) {
        const double d = v[k] - once[k];
        sum[k] += d;
        sq[k] += d * d;
      }
      return;
    }
    for (std::size_t i = 0; i < once.size(); ++i)
      for (std::size_t a = 0; a < na; ++a) {
        const std::size_t k = i * na + a;
        const double d = v[k] - albedo[a] * once[i];
        sum[k] += d;
        sq[k] += d * d;
      }
  }
  void add(const Chunk& c, const std::vector<double>& albedo) {
    add(flux_sum, flux_sq, c.flux);
    add(total_sum, total_sq, c.total);
    add(single_flux_sum, single_flux_sq, c.single_flux);
    add(single_total_sum, single_total_sq, c.single_total);
    add_multiple(multiple_flux_sum, multiple_flux_sq, c.flux, c.single_flux, albedo);
    add_multiple(multiple_total_sum, multiple_total_sq, c.total, c.single_total, albedo);
  }
};

// Batch means: chunk j's mean is m_j = S_j / M; the estimate is mean(m_j) and its
// standard error sqrt(Σ(m_j - m̄)² / (K (K - 1))).
struct BatchMeans {
  double K, M;  // chunks, photons per chunk
  void finish(double sum, double sq, double& mean, double& se) const {
    mean = sum / (K * M);
    const double m2 = std::max(0.0, sq / (M * M) - K * mean * mean);
    se = std::sqrt(m2 / (K * (K - 1.0)));
  }
};

// Every node's total and binned flux with their errors, and the multiply-scattered errors.
void write_estimates(const ChunkSums& s, const BatchMeans& bm, McTableData& t) {
  const std::size_t ne = t.eta.size(), na = t.albedo.size(), nb = t.r_edges.size() - 1;
  t.total.resize(ne * na);
  t.total_se.resize(ne * na);
  t.flux.resize(ne * na * nb);
  t.flux_se.resize(ne * na * nb);
  t.multiple_total_se.resize(ne * na);
  t.multiple_flux_se.resize(ne * na * nb);
  double unused;  // the multiply-scattered means are flux - α' q: only their errors are kept
  for (std::size_t e = 0; e < ne; ++e)
    for (std::size_t a = 0; a < na; ++a) {
      const std::size_t node = e * na + a;
      bm.finish(s.total_sum[node], s.total_sq[node], t.total[node], t.total_se[node]);
      bm.finish(s.multiple_total_sum[node], s.multiple_total_sq[node], unused, t.multiple_total_se[node]);
      for (std::size_t b = 0; b < nb; ++b) {
        const std::size_t src = (b * ne + e) * na + a;
        bm.finish(s.flux_sum[src], s.flux_sq[src], t.flux[t.slot(e, a, b)], t.flux_se[t.slot(e, a, b)]);
        bm.finish(s.multiple_flux_sum[src], s.multiple_flux_sq[src], unused,
                  t.multiple_flux_se[t.slot(e, a, b)]);
      }
    }
}

// The once-scattered flux: per node (g != 0), laid out as total and flux; or per unit
// albedo, [eta] and [eta][bin] (g = 0).
void write_single(const ChunkSums& s, const BatchMeans& bm, McTableData& t) {
  const std::size_t ne = t.eta.size(), na = t.albedo.size(), nb = t.r_edges.size() - 1;
  if (s.per_node > 1) {
    t.single_total.resize(ne * na);
    t.single_total_se.resize(ne * na);
    t.single_flux.resize(ne * na * nb);
    t.single_flux_se.resize(ne * na * nb);
    for (std::size_t e = 0; e < ne; ++e)
      for (std::size_t a = 0; a < na; ++a) {
        const std::size_t node = e * na + a;
        bm.finish(s.single_total_sum[node], s.single_total_sq[node], t.single_total[node],
                  t.single_total_se[node]);
        for (std::size_t b = 0; b < nb; ++b) {
          const std::size_t src = (b * ne + e) * na + a;
          bm.finish(s.single_flux_sum[src], s.single_flux_sq[src], t.single_flux[t.slot(e, a, b)],
                    t.single_flux_se[t.slot(e, a, b)]);
        }
      }
    return;
  }
  t.single_total.resize(ne);
  t.single_total_se.resize(ne);
  t.single_flux.resize(ne * nb);
  t.single_flux_se.resize(ne * nb);
  for (std::size_t e = 0; e < ne; ++e) {
    bm.finish(s.single_total_sum[e], s.single_total_sq[e], t.single_total[e], t.single_total_se[e]);
    for (std::size_t b = 0; b < nb; ++b)
      bm.finish(s.single_flux_sum[b * ne + e], s.single_flux_sq[b * ne + e],
                t.single_flux[t.single_slot(e, b)], t.single_flux_se[t.single_slot(e, b)]);
  }
}

}  // namespace

McTableData generate_mc_table(const McTableOptions& opt) {
  validate(opt);
  const std::size_t ne = opt.eta.size(), na = opt.albedo.size(), nb = opt.r_edges.size() - 1;
  const std::uint64_t chunks = opt.photons / opt.chunk_photons;
  ChunkSums sums(ne, na, nb, opt.g != 0.0 ? na : 1);
  detail::run_ordered_chunks<Chunk>(
      chunks, opt.threads,
      [&] {
        return [walker = std::make_shared<TableWalker>(opt)](std::uint64_t k, Chunk& c) {
          walker->run(k, c);
        };
      },
      [&](const Chunk& c, std::uint64_t done) {
        sums.add(c, opt.albedo);
        if (opt.progress) opt.progress(static_cast<double>(done) / chunks);
      });

  McTableData t;
  t.photons = opt.photons;
  t.seed = opt.seed;
  t.chunk_photons = opt.chunk_photons;
  t.roulette_weight = opt.roulette_weight;
  t.roulette_survival = opt.roulette_survival;
  t.eta = opt.eta;
  t.albedo = opt.albedo;
  t.r_edges = opt.r_edges;
  t.g = opt.g;
  const BatchMeans bm{static_cast<double>(chunks), static_cast<double>(opt.chunk_photons)};
  write_estimates(sums, bm, t);
  write_single(sums, bm, t);
  return t;
}

}  // namespace sss::profiles
