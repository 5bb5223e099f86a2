#include "profiles/McTableProfile.h"

#include "profiles/Integrate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sss::profiles {

double transport_decay_rate(double albedo) {
  if (!std::isfinite(albedo) || !(albedo > 0.0) || !(albedo < 1.0))
    throw std::invalid_argument("albedo: the transport decay rate needs an albedo in (0, 1), got " +
                                message_number(albedo));
  // f(κ) = α artanh(κ)/κ - 1 rises from α - 1 < 0 at κ = 0 to +∞ at κ = 1 (artanh(κ)/κ
  // is increasing), so the root is unique. Bisection in κ, 200 halvings to exhaustion of
  // double precision; each evaluation is one atanh, and this runs once per profile.
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (albedo * std::atanh(mid) / mid > 1.0)
      hi = mid;
    else
      lo = mid;
  }
  return 0.5 * (lo + hi);
}

namespace {

const auto str = sss::message_number;
// The start of the constructor's error for a table whose walks are too few at a medium
// (make_mc_table_profile falls back to another node on it).
constexpr std::string_view kTooFewAnnuli = "mc-table: fewer than two annuli";

// Interpolation weights along one axis: a cubic Hermite segment on [x_i, x_i+1] whose
// tangents are the derivatives of the parabola through the node and its two neighbours
// (Catmull-Rom generalised to a non-uniform grid; at the ends, the parabola through the
// three end nodes). The result is linear in the node values: up to 4 (node, weight)
// pairs. At a node (t = 0) the weights are exactly (1, 0, 0, 0), so a lookup at a table
// node returns the node. With two nodes this is linear interpolation; with one, that node.
struct AxisWeights {
  std::array<std::size_t, 4> node{};
  std::array<double, 4> weight{};
  int count = 0;
};

// The derivative at xs[k] of the parabola through xs[a], xs[b], xs[c] (k one of them), as
// weights of the three values: d/dx of the Lagrange basis polynomials.
void parabola_slope(const std::vector<double>& xs, std::size_t a, std::size_t b, std::size_t c,
                    std::size_t k, double scale, std::array<double, 4>& w, std::size_t base) {
  const std::array<std::size_t, 3> n = {a, b, c};
  for (std::size_t j : n) {
    double d;
    if (j == k) {
      d = 0.0;
      for (std::size_t m : n)
        if (m != k) d += 1.0 / (xs[k] - xs[m]);
    } else {
      d = 1.0 / (xs[j] - xs[k]);
      for (std::size_t m : n)
        if (m != j && m != k) d *= (xs[k] - xs[m]) / (xs[j] - xs[m]);
    }
    w[j - base] += scale * d;
  }
}

AxisWeights axis_weights(const std::vector<double>& xs, double x, bool linear = false) {
  AxisWeights out;
  const std::size_t n = xs.size();
  if (n == 1) {
    out.node[0] = 0;
    out.weight[0] = 1.0;
    out.count = 1;
    return out;
  }
  // The segment [xs[i], xs[i+1]] with xs[i] <= x (the last segment holds x = xs.back()).
  std::size_t i = static_cast<std::size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  i = std::min(i == 0 ? 0 : i - 1, n - 2);
  const double h = xs[i + 1] - xs[i];
  const double t = (x - xs[i]) / h;
  // Before the first node (only the α' axis goes there: u below the last albedo node, a
  // medium brighter than the table): the parabola through the first three nodes (Lagrange
  // weights), or the secant of the first two for the bilinear stencil. The quantities
  // interpolated there are smooth in u = √(1 - α') at u = 0: the total is 1 - a u + b u²
  // + O(u³) (the secant alone left the exact η = 1 total 0.12% low as α' -> 1), and
  // ln flux has its exp(-√3 u r) tail factor and a prefactor smooth in u.
  if (t < 0.0 && !linear && n >= 3) {
    for (std::size_t j = 0; j < 3; ++j) {
      double l = 1.0;
      for (std::size_t m = 0; m < 3; ++m)
        if (m != j) l *= (x - xs[m]) / (xs[j] - xs[m]);
      out.node[j] = j;
      out.weight[j] = l;
    }
    out.count = 3;
    return out;
  }
  if (t < 0.0) linear = true;
  const double h00 = (2.0 * t - 3.0) * t * t + 1.0, h01 = (3.0 - 2.0 * t) * t * t;
  const double h10 = ((t - 2.0) * t + 1.0) * t, h11 = (t - 1.0) * t * t;
  // Weights over nodes base .. base+3, base = i - 1 (or i at the first segment).
  const std::size_t base = i == 0 ? 0 : i - 1;
  std::array<double, 4> w{};
  w[i - base] += h00;
  w[i + 1 - base] += h01;
  if (n == 2 || linear) {  // linear: both tangents are the secant
    w[i - base] -= h10 + h11;
    w[i + 1 - base] += h10 + h11;
  } else {
    // Tangent at xs[i], times h (the Hermite form uses h m).
    if (i > 0)
      parabola_slope(xs, i - 1, i, i + 1, i, h10 * h, w, base);
    else
      parabola_slope(xs, i, i + 1, i + 2, i, h10 * h, w, base);
    // Tangent at xs[i+1].
    if (i + 2 < n)
      parabola_slope(xs, i, i + 1, i + 2, i + 1, h11 * h, w, base);
    else
      parabola_slope(xs, i - 1, i, i + 1, i + 1, h11 * h, w, base);
  }
  for (std::size_t j = 0; j < 4; ++j) {
    if (w[j] == 0.0 || base + j >= n) continue;  // exactly 0 at a node: not contributing
    out.node[static_cast<std::size_t>(out.count)] = base + j;
    out.weight[static_cast<std::size_t>(out.count)] = w[j];
    ++out.count;
  }
  return out;
}

// Checks the arrays' sizes and returns how many bins the lookup uses: the disc and the
// annuli after it as long as they are log-uniform (the lookup computes a bin's index from
// ln r). Annuli past the first irregular edge (e.g. a last edge rounded to a round number)
// are left to the tail, like unreliable ones.
// The once-scattered arrays are checked only for the lookup that uses them (apart): a
// table assembled in memory for the full lookup may leave them empty.
std::size_t check_table(const McTableData& t, bool apart) {
  const std::size_t nodes = t.eta.size() * t.albedo.size(), bins = t.bins();
  const std::size_t ne = t.eta.size();
  if (t.eta.empty() || t.albedo.empty() || bins < 4 || t.total.size() != nodes ||
      t.total_se.size() != nodes || t.flux.size() != nodes * bins || t.flux_se.size() != nodes * bins)
    throw std::invalid_argument(
        "mc-table: the table's arrays do not match its axes (eta, albedo, at least 4 radial bins)");
  // Once-scattered arrays per η (version 2), or per node (an anisotropic layer).
  const std::size_t ns = t.single_per_node() ? nodes : ne;
  if (apart && (t.single_total.size() != ns || t.single_total_se.size() != ns ||
                t.single_flux.size() != ns * bins || t.single_flux_se.size() != ns * bins ||
                t.multiple_total_se.size() != nodes || t.multiple_flux_se.size() != nodes * bins))
    throw std::invalid_argument(
        "mc-table: single scattering apart needs the table's once-scattered arrays (format "
        "version 2 or 3), sized to its axes");
  const double step = std::log(t.r_edges[2] / t.r_edges[1]);
  if (t.r_edges[0] != 0.0 || !(t.r_edges[1] > 0.0) || !(step > 0.0))
    throw std::invalid_argument("mc-table: r_edges must be 0, then ascending radii");
  // Uniform up to rounding: log_bin_edges-style edges r_1 e^{i step} agree to ~1e-15.
  std::size_t regular = 2;
  while (regular < bins &&
         std::fabs(std::log(t.r_edges[regular + 1] / t.r_edges[regular]) - step) <= 1e-9 * step)
    ++regular;
  if (regular < 4)
    throw std::invalid_argument("mc-table: r_edges must be log-uniform after the first edge");
  return regular;
}

}  // namespace

// The lookup, step by step (McTableProfile.h gives the overview).
//
// (α', η) interpolation. Nodes in α' are (nearly) uniform in u = √(1 - α'), and the
// profile depends on u exponentially (the diffusion tail is ~exp(-√3 u r)), so ln(flux)
// is close to linear in u and a cubic in u interpolates it well (ln(flux/α'), see below;
// where it does not, near α' = 1 in the far annuli, the normalisation to the total helps);
// the total behaves like 1 - c u near α' = 1 (Rd ≈ 1 - c√(1-α'), e.g. the η = 1 exact
// 1 - H(1)√(1-α') has H(1) ≈ 2.9), so it is interpolated in its own value.
// An annulus is "unreliable" if its flux is 0 or its relative standard error is above
// kMaxRelativeError at any node that contributes (non-zero weight): the log of a noisier
// value is biased and jumpy. Unreliable annuli are not enforced below; the
// reconstruction bridges them (interior) or the tail covers them (outer).
//
// Below the table's first α' (0.01) the profile is the first slice scaled by α'/α'_0:
// single scattering dominates a dark medium, R = α' R1 + O(α'²) with R1 the single-
// scattering profile per unit albedo, so the relative error of the scaling is O(α'_0),
// about 1%, and it vanishes at α'_0 (the extension is continuous there).
//
// Single scattering apart (McTableProfile.h). Every node's flux becomes its multiply-
// scattered part flux - α' q (McTable.h: exact for the same walks), clamped at 0, with
// the table's own standard error of that difference for the reliability test; the total
// likewise total - α' q_total. Light that scattered n >= 2 times carries α'^n, so the
// part is α'² M2 + O(α'³): ln(flux_ms/α'²) is what is interpolated (the ln α'² of a dark
// medium removed as ln α' was), the total as total_ms/α'² in value (Part::value_power),
// and below the first node the first slice is scaled by (α'/α'_0)², again with a relative
// error O(α'_0).
namespace {

// What is interpolated: every order, or the multiply-scattered part alone.
struct Part {
  const McTableData& t;
  bool apart;
  int power() const { return apart ? 2 : 1; }  // flux ∝ α'^power as α' -> 0
  // What is interpolated in value (the total, and in the normalisation the annuli left
  // unenforced) is divided by α'^value_power at the nodes and multiplied by it after:
  // 0 with every order (the total is ~α' as α' -> 0, which a cubic in u follows), 2 for the
  // multiply-scattered part, which is ~α'² M2 there: a cubic in u through its values bent
  // below zero between the first nodes of a coarse grid, while total/α'² = M2 + O(α') is
  // smooth, and near α' = 1 the factor α'² changes nothing.
  int value_power() const { return apart ? 2 : 0; }
  // At flat node index n = node(e, a).
  double total(std::size_t n) const {
    return apart ? t.multiple_total(n / t.albedo.size(), n % t.albedo.size()) : t.total[n];
  }
  double total_se(std::size_t n) const { return apart ? t.multiple_total_se[n] : t.total_se[n]; }
  double flux(std::size_t n, std::size_t b) const {
    return apart ? t.multiple_flux(n / t.albedo.size(), n % t.albedo.size(), b)
                 : t.flux[n * t.bins() + b];
  }
  double flux_se(std::size_t n, std::size_t b) const {
    return apart ? t.multiple_flux_se[n * t.bins() + b] : t.flux_se[n * t.bins() + b];
  }
};

struct Contribution {
  std::size_t node;
  double weight;
  double alpha;  // the node's α'
};
struct Stencil {
  std::array<Contribution, 16> node{};
  std::size_t count = 0;
};
// Where one medium sits in the table: the α' looked up (clamped into the table), the
// factor for α' below the first node ((α'/α'_0)^power), and the cubic and bilinear
// stencils.
struct Lookup {
  double alpha = 0.0, scale = 1.0;
  Stencil cubic, linear;
  double total = 0.0, total_se = 0.0;
};

Lookup lookup(const Coefficients& c, const Part& part) {
  const McTableData& table = part.t;
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  const double eta = c.eta;
  Lookup l;
  l.alpha = c.albedo_reduced();
  // Rounding: α' computed as σs'/σt' may land an ulp or so off a node; 1e-12 absorbs that.
  if (eta < table.eta.front() * (1.0 - 1e-12) || eta > table.eta.back() * (1.0 + 1e-12))
    throw std::invalid_argument("eta: mc-table covers eta in [" + str(table.eta.front()) + ", " +
                                str(table.eta.back()) + "], got " + str(eta));
  // Above the table's last α' (0.9999; Coefficients::validate keeps α' below 1 - 1e-12)
  // axis_weights extrapolates in u = √(1 - α') with the parabola through the last three
  // nodes (u = 0.01, 0.0256, 0.0413): in the diffusion limit the total is 1 - a u + b u²
  // + O(u³) and ln flux is smooth in u through the tail factor exp(-√3 u r). At η = 1
  // the extrapolated total is within 2.7e-5 relative of the exact 1 - H(1)u at α' =
  // 0.99997 (the preset cream's red) and 5.3e-5 as α' -> 1 - 1e-11
  // (ShippedExtrapolationPastTheLastAlbedoFollowsTheExactTotal); the far profile past the
  // table's last edge (1024 mfp) is the exponential tail.
  l.alpha = std::min(l.alpha, 1.0 - 1e-12);
  if (l.alpha < table.albedo.front()) {
    l.scale = std::pow(l.alpha / table.albedo.front(), part.power());
    l.alpha = table.albedo.front();
  }
  // The axes as interpolated: η directly, α' as u = √(1 - α') (ascending: α' reversed).
  const std::size_t na = table.albedo.size();
  std::vector<double> us(na);
  for (std::size_t j = 0; j < na; ++j) us[j] = std::sqrt(1.0 - table.albedo[na - 1 - j]);
  const double eta_q = std::clamp(eta, table.eta.front(), table.eta.back());
  const double u_q = std::sqrt(1.0 - l.alpha);
  auto stencil = [&](const AxisWeights& we, const AxisWeights& wa) {
    Stencil st;
    for (int i = 0; i < we.count; ++i)
      for (int j = 0; j < wa.count; ++j) {
        const std::size_t a = na - 1 - wa.node[static_cast<std::size_t>(j)];
        st.node[st.count++] = {table.node(we.node[static_cast<std::size_t>(i)], a),
                               we.weight[static_cast<std::size_t>(i)] *
                                   wa.weight[static_cast<std::size_t>(j)],
                               table.albedo[a]};
      }
    return st;
  };
  l.cubic = stencil(axis_weights(table.eta, eta_q), axis_weights(us, u_q));
  l.linear = stencil(axis_weights(table.eta, eta_q, true), axis_weights(us, u_q, true));
  for (std::size_t k = 0; k < l.cubic.count; ++k) {
    const Contribution& n = l.cubic.node[k];
    const double per = std::pow(n.alpha, -part.value_power());
    l.total += n.weight * part.total(n.node) * per;
    // The nodes share their random walks (McTable.h), so their errors are correlated:
    // Σ|w| se bounds the interpolated error whatever the correlation.
    l.total_se += std::fabs(n.weight) * part.total_se(n.node) * per;
  }
  const double back = std::pow(l.alpha, part.value_power());
  l.total = std::max(0.0, l.total * back * l.scale);
  l.total_se *= back * l.scale;
  return l;
}

}  // namespace

McTableTotal mc_table_total(const Coefficients& c, const McTableData& table,
                            bool single_scattering_apart) {
  check_table(table, single_scattering_apart);
  const Lookup l = lookup(c, Part{table, single_scattering_apart});
  return {l.total, l.total_se};
}

McTableProfile::McTableProfile(const Coefficients& c, bool single_scattering_apart)
    : McTableProfile(c, shipped_mc_table(), single_scattering_apart) {}

McTableProfile::McTableProfile(const Coefficients& c, const McTableData& table,
                               bool single_scattering_apart)
    : single_scattering_apart_(single_scattering_apart) {
  const std::size_t bins_used = check_table(table, single_scattering_apart);
  const Part part{table, single_scattering_apart};
  const Lookup l = lookup(c, part);
  sigma_tp_ = c.sigma_t_reduced();
  const double eta = c.eta, alpha = l.alpha, scale = l.scale;
  const Stencil& cubic = l.cubic;
  const Stencil& linear = l.linear;
  total_ = l.total;
  total_se_ = l.total_se;
  r_min_mm_ = kMinRadiusMfp / sigma_tp_;
  // A medium that does not scatter (σs' = 0: α' = 0) reflects nothing: R ≡ 0, as the
  // diffusion models give. (Without this, ln(0) flux made every R(r) NaN.)
  if (!(scale > 0.0)) {
    zero_ = true;
    total_ = total_se_ = 0.0;
    support_mfp_ = 1.0;
    target_flux_.assign(table.bins(), 0.0);
    enforced_.assign(table.bins(), 0);
    return;
  }

  // Per annulus: ln(flux / α'^p) with the cubic stencil, or, where one of its nodes is
  // unreliable, with the bilinear one (the two bracketing nodes per axis; at a node both
  // are that node); unreliable at those too: not enforced. Dividing by the node's α'^p
  // (p = 1, or 2 for the multiply-scattered part) removes the ln α' singularity of a dark
  // medium (flux ∝ α'^p as α' → 0, a log that bends steeply across the first nodes); near
  // α' = 1 it changes nothing.
  const double power = part.power();
  auto interpolate = [&](const Stencil& st, std::size_t b, double& out) {
    double lnf = 0.0;
    for (std::size_t k = 0; k < st.count; ++k) {
      const double f = part.flux(st.node[k].node, b);
      if (!(f > 0.0 && part.flux_se(st.node[k].node, b) <= kMaxRelativeError * f)) return false;
      lnf += st.node[k].weight * std::log(f / std::pow(st.node[k].alpha, power));
    }
    out = std::pow(alpha, power) * scale * std::exp(lnf);
    return true;
  };
  const std::size_t bins = table.bins();
  target_flux_.assign(bins, 0.0);
  enforced_.assign(bins, 0);
  for (std::size_t b = 0; b < bins_used; ++b)
    enforced_[b] = interpolate(cubic, b, target_flux_[b]) || interpolate(linear, b, target_flux_[b]);
  // Past the peak of the flux per annulus, the enforced range ends at the first unreliable
  // annulus: a "reliable" one beyond it is a few lucky walks (batch means from few chunks
  // can underestimate their own error), and the tail describes that region better.
  {
    std::size_t peak = 0;
    for (std::size_t b = 1; b < bins_used; ++b)
      if (enforced_[b] && (!enforced_[peak] || target_flux_[b] > target_flux_[peak])) peak = b;
    bool cut = false;
    for (std::size_t b = peak + 1; b < bins_used; ++b) {
      cut = cut || !enforced_[b];
      if (cut) enforced_[b] = 0, target_flux_[b] = 0.0;
    }
  }
  for (std::size_t b = 0; b < bins; ++b)
    if (!enforced_[b]) target_flux_[b] = 0.0;
  // Normalisation: the enforced fluxes are scaled so that they, with the other annuli and
  // the exits past the last edge interpolated in value (with the total's cubic weights),
  // add up to the interpolated total. At a node the factor is 1 (up to rounding: the
  // walks' fluxes and beyond-edge exits add up to their total). Between nodes it removes
  // the log interpolation's error in the flux sum: near α' = 1, where the far annuli hold
  // much of the flux and ln(flux) bends in u (the diffusion prefactor (1 + σtr r)), the
  // log-interpolated fluxes summed to up to 0.07% less than the interpolated total
  // (measured at α' = 0.9998, η = 1), while the total's interpolation follows the exact
  // η = 1 total 1 - H(1)√(1-α') within the table's noise. The price: a factor that is 1
  // at the nodes and up to ~1.002 between the last two (α' > 0.9993), so there R near
  // the source, which hardly changes with α', can dip by that much between the nodes.
  // (Sharing the correction out only where value and log interpolation disagree was
  // tried: value interpolation of the far annuli, whose fluxes differ by orders of
  // magnitude across the stencil, is itself wrong there.)
  {
    // (With every order value_power is 0 and both powers are exactly 1.)
    const double scale_v = scale * std::pow(alpha, part.value_power());
    double sum = 0.0;
    for (std::size_t k = 0; k < cubic.count; ++k) {
      const std::size_t n = cubic.node[k].node;
      const double w = cubic.node[k].weight * std::pow(cubic.node[k].alpha, -part.value_power());
      double node_sum = 0.0;
      for (std::size_t b = 0; b < bins; ++b) {
        const double f = part.flux(n, b);
        node_sum += f;
        if (!enforced_[b]) sum += scale_v * w * f;
      }
      sum += scale_v * w * (part.total(n) - node_sum);
    }
    double enforced_sum = 0.0;
    for (std::size_t b = 0; b < bins; ++b) enforced_sum += target_flux_[b];
    const double factor = (total_ - sum) / enforced_sum;
    // A factor far from 1 would mean the unreliable annuli carry much of the flux: keep
    // the fluxes as interpolated then (never seen with the shipped table).
    if (factor > 0.99 && factor < 1.01) {
      for (double& f : target_flux_) f *= factor;
      flux_scale_ = factor;
    }
  }

  // Histopolation in x = ln r (optical units). q(x) = 2π r² R(r), so the flux through
  // an annulus [r_k, r_k+1) is ∫ q dx over [x_k, x_k+1]: the log-uniform annuli are equal
  // intervals of width Δ in x. Node k sits at the centre c_k = x_1 + (k - ½)Δ of bin k;
  // node 0, at x_1 - Δ/2, belongs to the disc [0, r_1). φ = ln q is a uniform Catmull-Rom
  // spline through the nodes 0..K (K: the last enforced annulus), and outside them:
  //  - below c_0, with every order: φ is linear with slope s: q ∝ r^s, R ∝ r^{s-2}. Near
  //    the source a pencil beam's single scattering gives R ~ 1/r (s = 1) and multiple
  //    scattering an R that grows only like ln(1/r) (s -> 2); s is the slope between the
  //    first two enforced annuli, clamped to [1, 2] (outside that range it can only be
  //    noise). The disc's flux sets node 0's value.
  //  - below c_0, single scattering apart: no 1/r term is left. Twice-scattered light
  //    makes R grow like ln(1/r) at the source: the first event on the beam at depth z1,
  //    the second at x2, two 1/d² propagators whose product integrated over x2 is ~1/|z1 -
  //    r| (a convolution of two 1/d² kernels in 3D), and ∫ dz1/|z1 - r| ~ ln(1/r); higher
  //    orders are finite there (PBD's ms term has the same ln r, PhotonBeamDiffusion.h).
  //    A power law would overshoot that by orders of magnitude over the 6 decades from
  //    the first node to min_radius, so R = R_0 (1 + (2 - s)(x_0 - x)) below x_0 = c_0:
  //    R ∝ ln(r_c/r) with r_c = r_0 e^{1/(2-s)}, whose slope d ln q/dx is s at c_0 (C1
  //    with the spline), s a clamped estimate as above but fitted over the first decade
  //    of enforced annuli (see inner_fit; s = 2: R constant). Its integral
  //    below c_0 is q_0 (1/2 + (2 - s)/4). Annuli before the first enforced one follow
  //    the same law from that annulus down (so the law below c_0 is its continuation,
  //    with R ∝ 1 + (2 - s)(c_first - x)).
  //  - above c_K, R(r) = R(r_K) exp(-κ (r - r_K)), an exponential tail in r continuous
  //    with node K (and C1 with the spline, whose tangent at c_K is the tail's). κ is the
  //    asymptotic transport decay rate κ0 (transport_decay_rate: the slowest mode of
  //    isotropic transport decays like e^{-κ0 r}), or the rate between the last two
  //    enforced nodes if that is steeper (the power-law factor in front of e^{-κ0 r}
  //    steepens the profile at finite r).
  // An unreliable annulus between enforced ones gets the value linear in x between its
  // enforced neighbours; one before the first enforced annulus the law below c_0 (power
  // or log), continued from the first enforced annulus.
  // The node values are adjusted by the fixed point φ_k += ω ln(F_k / I_k), I_k being the
  // spline's integral over bin k (6-point Gauss-Legendre per half bin: the integrand
  // exp(cubic) is smooth on a half bin; the tail's half bin in closed form), until every
  // enforced bin's integral matches its flux to 1e-12, at most 60 steps. Convergence:
  // linearised, ln I_k responds to the node values through the integral of the
  // Catmull-Rom cardinal function over a bin, 0.839 for its own node, 0.094 for each
  // neighbour, -0.013 for the next; the step's error factor 1 - ωλ then ranges over
  // λ ∈ [0.625, 1] (alternating to smooth modes), 0.375 at worst for ω = 1 and 0.23 for
  // ω = 1.2 (measured: ~0.19 per step, 20 steps from a flat start). s and κ are
  // re-estimated during the first 4 steps only: fed back every step they slow the
  // iteration (measured 0.6 per step), and 4 steps leave them within ~1% of their limit.
  const double x1 = std::log(table.r_edges[1]);
  const double dx = std::log(table.r_edges[2] / table.r_edges[1]);
  std::size_t K = 0, first = 0, second = 0, enforced_annuli = 0;
  for (std::size_t b = 1; b < bins_used; ++b)
    if (enforced_[b]) {
      K = b;
      if (enforced_annuli == 0) first = b;
      if (enforced_annuli == 1) second = b;
      ++enforced_annuli;
    }
  if (enforced_annuli < 2)
    throw std::invalid_argument(std::string(kTooFewAnnuli) + " with a reliable flux at albedo " +
                                str(c.albedo_reduced()) + ", eta " + str(eta) +
                                " (the table's photon budget is too small)");
  std::vector<double> phi(K + 1, 0.0), centre(K + 1);
  for (std::size_t k = 0; k <= K; ++k) {
    centre[k] = x1 + (static_cast<double>(k) - 0.5) * dx;
    if (enforced_[k]) phi[k] = std::log(target_flux_[k] / dx);
  }
  // s0: the slope of φ at c_0, which the law below c_0 continues (= s, or for the log
  // law anchored at c_first (see fill), 2 - k0 with k0 = (2 - s)/(1 + (2 - s)(c_first - c_0))).
  double s = 1.5, s0 = 1.5, kappa = 0.0;
  const double kappa0 = transport_decay_rate(alpha);
  const double rK = std::exp(centre[K]);
  // Apart: the least-squares slope of φ over the enforced annuli within a decade of the
  // first one (16 on the shipped grid). The first two alone are the noisiest annuli of
  // the multiply-scattered part (relative errors 10-40% near the source, where the once-
  // scattered light dominates the walks' exits): at η = 1.4 their slope sat at the clamp
  // 2 for 5 of 6 albedos from 0.01 to 0.9999. Over the decade it is 1.53-2 on the shipped
  // table (at the clamp for 10% of 3131 media swept over η and α'), as ln(r_c/r) gives
  // there (2 - 1/ln(r_c/r), 1.6-1.8 for r_c ~ 0.03-1 mfp at r ~ 0.005 mfp).
  auto inner_fit = [&] {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t k = first; k <= K && centre[k] <= centre[first] + std::log(10.0); ++k) {
      if (!enforced_[k]) continue;
      const double x = centre[k] - centre[first];
      n += 1, sx += x, sy += phi[k], sxx += x * x, sxy += x * phi[k];
    }
    const double det = n * sxx - sx * sx;
    return det > 0.0 ? (n * sxy - sx * sy) / det
                     : (phi[second] - phi[first]) / (centre[second] - centre[first]);
  };
  auto fill = [&](bool rates) {
    if (rates)
      s = std::clamp(single_scattering_apart_
                         ? inner_fit()
                         : (phi[second] - phi[first]) / (centre[second] - centre[first]),
                     1.0, 2.0);
    // Before the first enforced annulus, the law that holds below c_0 (above), anchored
    // at the first enforced node: the power law φ = φ_f - s (c_f - x), or the log law
    // φ = φ_f - 2 (c_f - x) + ln(1 + (2 - s)(c_f - x)).
    const double k_log = 2.0 - s;
    const std::size_t anchor = enforced_[0] ? 0 : first;
    s0 = single_scattering_apart_
             ? 2.0 - k_log / (1.0 + k_log * (centre[anchor] - centre[0]))
             : s;
    std::size_t prev = bins;  // none yet
    for (std::size_t k = 0; k <= K; ++k) {
      if (enforced_[k]) {
        prev = k;
        continue;
      }
      if (prev == bins) {
        const double d = centre[first] - centre[k];
        phi[k] = single_scattering_apart_ ? phi[first] - 2.0 * d + std::log1p(k_log * d)
                                          : phi[first] - s * d;
      } else {
        std::size_t next = k + 1;
        while (!enforced_[next]) ++next;  // K is enforced
        const double t = (centre[k] - centre[prev]) / (centre[next] - centre[prev]);
        phi[k] = phi[prev] + t * (phi[next] - phi[prev]);
      }
    }
    std::size_t p = K - 1;
    while (!enforced_[p]) --p;  // `first` < K is enforced
    const double rp = std::exp(centre[p]);
    const double k2 = ((phi[p] - 2.0 * centre[p]) - (phi[K] - 2.0 * centre[K])) / (rK - rp);
    if (rates) kappa = std::max(kappa0, k2);
  };
  // Segment k (c_k..c_k+1) in t ∈ [0, 1]: φ = a0 + a1 t + a2 t² + a3 t³.
  std::vector<double> seg(4 * K);
  auto build_segments = [&] {
    auto tangent = [&](std::size_t k) {  // dφ/dt, t in units of Δ
      if (k == 0) return s0 * dx;
      if (k == K) return (2.0 - kappa * rK) * dx;
      return 0.5 * (phi[k + 1] - phi[k - 1]);
    };
    for (std::size_t k = 0; k < K; ++k) {
      const double p0 = phi[k], p1 = phi[k + 1], m0 = tangent(k), m1 = tangent(k + 1);
      seg[4 * k] = p0;
      seg[4 * k + 1] = m0;
      seg[4 * k + 2] = 3.0 * (p1 - p0) - 2.0 * m0 - m1;
      seg[4 * k + 3] = 2.0 * (p0 - p1) + m0 + m1;
    }
  };
  const GaussLegendreRule& gl = gauss_legendre(6);
  // ∫ exp(segment k) over t ∈ [t0, t0 + ½], in x units.
  auto seg_integral = [&](std::size_t k, double t0) {
    const double* a = &seg[4 * k];
    double sum = 0.0;
    for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
      const double t = t0 + 0.25 * (gl.nodes[i] + 1.0);
      sum += gl.weights[i] * std::exp(a[0] + t * (a[1] + t * (a[2] + t * a[3])));
    }
    return 0.25 * dx * sum;
  };
  // ∫ exp(tail) over x ∈ [c_K, c_K + Δ/2], in closed form (the tail can fall by many
  // orders of magnitude across a half bin, which no fixed quadrature follows):
  // q_K/r_K² ∫ r e^{-κ(r - r_K)} dr over [r_K, r_K + d] = q_K/r_K² [(1 - E)(r_K/κ + 1/κ²) - d E/κ],
  // E = e^{-κ d}.
  const double r_edge = std::exp(centre[K] + 0.5 * dx), d_tail = r_edge - rK;
  auto tail_integral = [&] {
    const double E = std::exp(-kappa * d_tail), one_minus_E = -std::expm1(-kappa * d_tail);
    return std::exp(phi[K]) / (rK * rK) *
           (one_minus_E * (rK / kappa + 1.0 / (kappa * kappa)) - d_tail * E / kappa);
  };
  // ∫ q dx below c_0: q_0/s0 for the power law, q_0 (1/2 + (2 - s0)/4) for the log law
  // (∫_0^∞ e^{-2t} (1 + k t) dt = 1/2 + k/4).
  auto inner_integral = [&] {
    return single_scattering_apart_ ? std::exp(phi[0]) * (0.5 + 0.25 * (2.0 - s0))
                                    : std::exp(phi[0]) / s0;
  };
  auto bin_integral = [&](std::size_t k) {
    if (k == 0) return inner_integral() + seg_integral(0, 0.0);
    return seg_integral(k - 1, 0.5) + (k < K ? seg_integral(k, 0.0) : tail_integral());
  };
  constexpr int kRateIterations = 4;
  constexpr double kRelax = 1.2;
  for (iterations_ = 0; iterations_ < 60; ++iterations_) {
    fill(iterations_ < kRateIterations);
    build_segments();
    residual_ = 0.0;
    std::vector<double> step(K + 1, 0.0);
    for (std::size_t k = 0; k <= K; ++k) {
      if (!enforced_[k]) continue;
      step[k] = std::log(target_flux_[k] / bin_integral(k));
      // Written so that a NaN step raises the residual (std::max would drop it).
      if (!(std::fabs(step[k]) <= residual_)) residual_ = std::fabs(step[k]);
    }
    if (!std::isfinite(residual_))
      throw std::runtime_error("mc-table: the R(r) reconstruction diverged at albedo " +
                               str(c.albedo_reduced()) + ", eta " + str(eta));
    if (residual_ < 1e-12) break;
    for (std::size_t k = 0; k <= K; ++k) phi[k] += kRelax * step[k];
  }
  // Not converged in 60 iterations (never seen): the segments must still describe the
  // φ the evaluation constants below are taken from.
  if (!(residual_ < 1e-12)) {
    fill(false);
    build_segments();
  }

  // Evaluation constants in mm: u = ln r_mm = x - ln σt', ψ = ln R_mm = 2 ln σt' + φ - 2x - ln 2π.
  const double ls = std::log(sigma_tp_);
  const double c2 = 2.0 * ls - std::log(2.0 * std::numbers::pi);
  u_lo_ = centre[0] - ls;
  inv_du_ = 1.0 / dx;
  lo_a_ = c2 + phi[0] - 2.0 * centre[0];
  if (single_scattering_apart_) {
    lo_b_ = 0.0;
    lo_log_ = 2.0 - s0;
  } else {
    lo_b_ = s0 - 2.0;
    lo_log_ = 0.0;
  }
  inner_slope_ = s0;
  coef_.resize(4 * K);
  for (std::size_t k = 0; k < K; ++k) {
    coef_[4 * k] = seg[4 * k] + c2 - 2.0 * centre[k];
    coef_[4 * k + 1] = seg[4 * k + 1] - 2.0 * dx;
    coef_[4 * k + 2] = seg[4 * k + 2];
    coef_[4 * k + 3] = seg[4 * k + 3];
  }
  r_tail_ = rK / sigma_tp_;
  tail_k_ = kappa * sigma_tp_;
  tail_a_ = std::exp(c2 + phi[K] - 2.0 * centre[K]);
  r_min_mm_ = kMinRadiusMfp / sigma_tp_;
  kappa_ = kappa;
  tail_r_ = rK;

  // Support: r R = q / (2π r) = e^{φ - x}/2π. Its peak is at a node, or in the tail at
  // r = 1/κ if that lies past r_K (r e^{-κ r} peaks there).
  double peak = -std::numeric_limits<double>::infinity();
  std::size_t peak_k = 0;
  for (std::size_t k = 0; k <= K; ++k)
    if (phi[k] - centre[k] > peak) peak = phi[k] - centre[k], peak_k = k;
  // ln(r R 2π) in the tail: φ_K - 2c_K + ln r - κ (r - r_K).
  auto tail_log = [&](double r) { return phi[K] - 2.0 * centre[K] + std::log(r) - kappa * (r - rK); };
  const double r_turn = std::max(rK, 1.0 / kappa);
  peak = std::max(peak, tail_log(r_turn));
  const double floor_log = peak + std::log(1e-8);
  support_mfp_ = 0.0;
  for (std::size_t k = peak_k + 1; k <= K && support_mfp_ == 0.0; ++k)
    if (phi[k] - centre[k] < floor_log) support_mfp_ = std::exp(centre[k]);
  if (support_mfp_ == 0.0) {
    // tail_log decreases past r_turn: bracket the crossing by doubling, then bisect.
    double lo = r_turn, hi = 2.0 * r_turn;
    while (tail_log(hi) > floor_log) lo = hi, hi *= 2.0;
    for (int i = 0; i < 100 && hi - lo > 1e-12 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (tail_log(mid) > floor_log ? lo : hi) = mid;
    }
    support_mfp_ = hi;
  }
}

double McTableProfile::reflectance(double r) const {
  if (zero_) return 0.0;
  if (!(r >= r_min_mm_)) r = r_min_mm_;  // also a NaN r: no undefined index below
  if (r >= r_tail_) return tail_a_ * std::exp(-tail_k_ * (r - r_tail_));
  const double u = std::log(r);
  if (u < u_lo_) return std::exp(lo_a_ + lo_b_ * (u - u_lo_)) * (1.0 + lo_log_ * (u_lo_ - u));
  const double v = (u - u_lo_) * inv_du_;
  const std::size_t last = coef_.size() / 4 - 1;
  const std::size_t j = std::min(static_cast<std::size_t>(v), last);
  const double t = v - static_cast<double>(j);
  const double* a = &coef_[4 * j];
  return std::exp(a[0] + t * (a[1] + t * (a[2] + t * a[3])));
}

McTableGBracket mc_table_g_bracket(double g) {
  const McTableData& iso = shipped_mc_table();
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  McTableGBracket b;
  b.lo = &iso;
  if (!(g > 0.0)) return b;  // g <= 0 (and NaN, which Coefficients::validate refuses)
  double g_prev = 0.0;
  for (const McTableData& layer : layers) {
    if (g == layer.g) {
      b.lo = &layer;
      return b;
    }
    if (g < layer.g) {
      b.hi = &layer;
      b.t = (std::log1p(-g) - std::log1p(-g_prev)) / (std::log1p(-layer.g) - std::log1p(-g_prev));
      return b;
    }
    b.lo = &layer;
    g_prev = layer.g;
  }
  return b;  // above the last layer: that layer alone
}

std::optional<std::string> mc_table_g_warning(double g) {
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  const double g_max = layers.empty() ? 0.0 : layers.back().g;
  if (g < 0.0)
    return "g " + str(g) + " < 0: mc-table tabulates 0 <= g <= " + str(g_max) +
           "; looked up in the isotropic table by the similarity relation (sigma_s' = sigma_s "
           "(1 - g))";
  if (g > g_max)
    return "g " + str(g) + " > " + str(g_max) + ": mc-table tabulates 0 <= g <= " + str(g_max) +
           "; looked up in the g = " + str(g_max) +
           " layer by the similarity relation (its reduced coefficients)";
  return std::nullopt;
}

std::vector<std::string> mc_table_g_warnings(const Medium& medium) {
  std::vector<std::string> out;
  for (int c = 0; c < 3; ++c) {
    bool said = false;
    for (int k = 0; k < c; ++k) said |= medium.g[k] == medium.g[c];
    if (said) continue;
    if (const auto w = mc_table_g_warning(medium.g[c]))
      out.push_back(std::string("g[") + "RGB"[c] + "]: " + *w);
  }
  return out;
}

McTableTotal mc_table_total_any_g(const Coefficients& c, bool single_scattering_apart) {
  const McTableGBracket b = mc_table_g_bracket(c.g);
  const McTableTotal lo = mc_table_total(c, *b.lo, single_scattering_apart);
  if (!b.hi) return lo;
  const McTableTotal hi = mc_table_total(c, *b.hi, single_scattering_apart);
  // The layers' walks share their seed, so their errors may be correlated: the weighted
  // sum bounds the interpolated error whatever the correlation.
  return {(1.0 - b.t) * lo.total + b.t * hi.total,
          (1.0 - b.t) * lo.stderr_ + b.t * hi.stderr_};
}

namespace {

// R(r) between two g nodes: (1 - t) R_lo + t R_hi, every quantity likewise.
class McTableGBlend final : public RadialProfile {
 public:
  McTableGBlend(std::unique_ptr<McTableProfile> lo, std::unique_ptr<McTableProfile> hi, double t)
      : lo_(std::move(lo)), hi_(std::move(hi)), t_(t) {}
  double reflectance(double r) const override {
    return (1.0 - t_) * lo_->reflectance(r) + t_ * hi_->reflectance(r);
  }
  double total_reflectance() const override {
    return (1.0 - t_) * lo_->total_reflectance() + t_ * hi_->total_reflectance();
  }
  double support_radius() const override {
    return std::max(lo_->support_radius(), hi_->support_radius());
  }
  double inner_radius() const override { return lo_->inner_radius(); }

 private:
  std::unique_ptr<McTableProfile> lo_, hi_;
  double t_;
};

// The lookup in table t, or null where t's walks are too few to shape R(r) there (the
// constructor's kTooFewAnnuli error); any other error propagates.
std::unique_ptr<McTableProfile> try_profile(const Coefficients& c, const McTableData& t,
                                            bool apart) {
  try {
    return std::make_unique<McTableProfile>(c, t, apart);
  } catch (const std::invalid_argument& e) {
    if (std::string_view(e.what()).starts_with(kTooFewAnnuli)) return nullptr;
    throw;
  }
}

}  // namespace

std::unique_ptr<RadialProfile> make_mc_table_profile(const Coefficients& c,
                                                     bool single_scattering_apart) {
  if (auto e = c.validate()) throw std::invalid_argument(e->what());
  const McTableGBracket b = mc_table_g_bracket(c.g);
  // A layer's walks (2^18, a sixteenth of the isotropic table's) can be too few to shape
  // R(r) at its darkest nodes for a high η and g: at α' = 0.01 and g = 0.95 a walk's real
  // albedo is 0.17 and HG sends almost nothing back up, and at η = 2.5 little of that
  // leaves. Where a layer's lookup finds fewer than two reliable annuli, the next node
  // towards g = 0 stands in for it (ultimately the isotropic table, 2^22 walks, whose
  // errors propagate), so every medium that had a profile before the layers still has
  // one. Each profile is built once.
  std::unique_ptr<McTableProfile> hi =
      b.hi ? try_profile(c, *b.hi, single_scattering_apart) : nullptr;
  const McTableData* node = b.lo;
  std::unique_ptr<McTableProfile> lo;
  const std::vector<McTableData>& layers = shipped_mc_table_layers();
  while (node != &shipped_mc_table() && !(lo = try_profile(c, *node, single_scattering_apart))) {
    const auto k = static_cast<std::size_t>(node - layers.data());
    node = k == 0 ? &shipped_mc_table() : &layers[k - 1];
    hi.reset();  // no longer the neighbour of the node in use
  }
  if (!lo) lo = std::make_unique<McTableProfile>(c, *node, single_scattering_apart);
  if (!hi) return lo;
  return std::make_unique<McTableGBlend>(std::move(lo), std::move(hi), b.t);
}

}  // namespace sss::profiles
