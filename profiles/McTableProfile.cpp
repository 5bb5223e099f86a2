#include "profiles/McTableProfile.h"

#include "profiles/Integrate.h"
#include "profiles/McTableSpline.h"

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
constexpr std::string_view kTooFewAnnuli = McTableProfile::kTooFewAnnuli;

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

// The parabola through the first three nodes at x (Lagrange weights).
AxisWeights first_parabola(const std::vector<double>& xs, double x) {
  AxisWeights out;
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

// The cubic Hermite weights at t in segment i over nodes base .. base+3 (base = i - 1, or
// i at the first segment); the tangents are the parabolas' slopes through the neighbours,
// or the secant (`linear`, or only two nodes).
std::array<double, 4> hermite_weights(const std::vector<double>& xs, std::size_t i, double t, bool linear,
                                      std::size_t base) {
  const std::size_t n = xs.size();
  const double h = xs[i + 1] - xs[i];
  const double h00 = (2.0 * t - 3.0) * t * t + 1.0, h01 = (3.0 - 2.0 * t) * t * t;
  const double h10 = ((t - 2.0) * t + 1.0) * t, h11 = (t - 1.0) * t * t;
  std::array<double, 4> w{};
  w[i - base] += h00;
  w[i + 1 - base] += h01;
  if (n == 2 || linear) {  // linear: both tangents are the secant
    w[i - base] -= h10 + h11;
    w[i + 1 - base] += h10 + h11;
    return w;
  }
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
  return w;
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
  const double t = (x - xs[i]) / (xs[i + 1] - xs[i]);
  // Before the first node (only the α' axis goes there: u below the last albedo node, a
  // medium brighter than the table): the parabola through the first three nodes, or the
  // secant of the first two for the bilinear stencil. The quantities interpolated there
  // are smooth in u = √(1 - α') at u = 0: the total is 1 - a u + b u² + O(u³) (the secant
  // alone left the exact η = 1 total 0.12% low as α' -> 1), and ln flux has its
  // exp(-√3 u r) tail factor and a prefactor smooth in u.
  if (t < 0.0 && !linear && n >= 3) return first_parabola(xs, x);
  if (t < 0.0) linear = true;
  const std::size_t base = i == 0 ? 0 : i - 1;
  const std::array<double, 4> w = hermite_weights(xs, i, t, linear, base);
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

// Which annuli the spline must reproduce, and their fluxes (`target`, 0 elsewhere).
void enforce_annuli(const Part& part, const Lookup& l, std::size_t bins_used, std::vector<double>& target,
                    std::vector<char>& enforced) {
  const double alpha = l.alpha, scale = l.scale;
  const Stencil& cubic = l.cubic;
  const Stencil& linear = l.linear;
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
      if (!(f > 0.0 && part.flux_se(st.node[k].node, b) <= McTableProfile::kMaxRelativeError * f)) return false;
      lnf += st.node[k].weight * std::log(f / std::pow(st.node[k].alpha, power));
    }
    out = std::pow(alpha, power) * scale * std::exp(lnf);
    return true;
  };
  const std::size_t bins = part.t.bins();
  target.assign(bins, 0.0);
  enforced.assign(bins, 0);
  for (std::size_t b = 0; b < bins_used; ++b)
    enforced[b] = interpolate(cubic, b, target[b]) || interpolate(linear, b, target[b]);
  // Past the peak of the flux per annulus, the enforced range ends at the first unreliable
  // annulus: a "reliable" one beyond it is a few lucky walks (batch means from few chunks
  // can underestimate their own error), and the tail describes that region better.
  {
    std::size_t peak = 0;
    for (std::size_t b = 1; b < bins_used; ++b)
      if (enforced[b] && (!enforced[peak] || target[b] > target[peak])) peak = b;
    bool cut = false;
    for (std::size_t b = peak + 1; b < bins_used; ++b) {
      cut = cut || !enforced[b];
      if (cut) enforced[b] = 0, target[b] = 0.0;
    }
  }
  for (std::size_t b = 0; b < bins; ++b)
    if (!enforced[b]) target[b] = 0.0;
}

// Normalisation: the factor by which the enforced fluxes are scaled so that they, with the other annuli and
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
double normalisation(const Part& part, const Lookup& l, double total, const std::vector<double>& target,
                     const std::vector<char>& enforced) {
  const double alpha = l.alpha, scale = l.scale;
  const Stencil& cubic = l.cubic;
  const std::size_t bins = part.t.bins();
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
      if (!enforced[b]) sum += scale_v * w * f;
    }
    sum += scale_v * w * (part.total(n) - node_sum);
  }
  double enforced_sum = 0.0;
  for (std::size_t b = 0; b < bins; ++b) enforced_sum += target[b];
  return (total - sum) / enforced_sum;
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

  enforce_annuli(part, l, bins_used, target_flux_, enforced_);

  // A factor far from 1 would mean the unreliable annuli carry much of the flux: keep
  // the fluxes as interpolated then (never seen with the shipped table).
  const double factor = normalisation(part, l, total_, target_flux_, enforced_);
  if (factor > 0.99 && factor < 1.01) {
    for (double& f : target_flux_) f *= factor;
    flux_scale_ = factor;
  }

  // The spline through the enforced fluxes (McTableSpline.cpp: "Histopolation").
  const McTableSpline spline =
      fit_mc_table_spline(table.r_edges, bins_used, target_flux_, enforced_, alpha, single_scattering_apart_,
                          std::string(kTooFewAnnuli), "albedo " + str(c.albedo_reduced()) + ", eta " + str(eta));
  iterations_ = spline.iterations;
  residual_ = spline.residual;
  set_evaluation(spline);
  support_mfp_ = mc_table_support_mfp(spline);
}

void McTableProfile::set_evaluation(const McTableSpline& spline) {
  const std::size_t K = spline.K;
  const double dx = spline.dx, s0 = spline.s0, kappa = spline.kappa, rK = spline.rK;
  const std::vector<double>& phi = spline.phi;
  const std::vector<double>& centre = spline.centre;
  const std::vector<double>& seg = spline.seg;
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

}  // namespace sss::profiles
