// ScatterKernel: the disc-averaged profile K(d) of the reference renderer.
//
// The references here are independent of ScatterKernel.cpp's quadrature:
// - the disc integral in polar coordinates about x_o (angle, then radius along each ray
//   through profiles::integrate_log), instead of the kernel's rings about x_o;
// - the profiles' own totals (closed forms for the dipoles and the multipole, PBD's own
//   radial quadrature), which Σ_i K(|x_o − x_i|) A must reproduce over a plane of points;
// - the mean-value bound |K(d) − R(d)| ≤ (a²/8) max |ΔR| over the disc.
#include "reference/ScatterKernel.h"

#include "profiles/Integrate.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using namespace sss;
using namespace sss::reference;
using profiles::Model;
using profiles::RadialProfile;
using profiles::RgbProfile;

namespace {

constexpr double kPi = std::numbers::pi;

profiles::Medium preset(const char* name) {
  return profiles::preset_medium(*profiles::find_preset(name));
}

double disc_radius(double area) { return std::sqrt(area / kPi); }

// ∫_w0^w1 g, `panels` Gauss–Legendre panels of 16 points.
template <class G>
double gl(G&& g, double w0, double w1, int panels) {
  return profiles::integrate([&](double w) { return g(w); }, w0, w1, panels, 16);
}

// The disc average by polar coordinates about x_o (disc centre at the origin, x_o at
// distance d): K = 1/(πa²) ∫ dψ ∫ f(ρ) ρ dρ over the part of each ray inside the disc.
// F(x) = ∫_0^x f ρ dρ by geometric panels (profiles::integrate_log), resolving R down
// to 1e-6 of its inner radius (its 1/r peak for PBD and Burley). R is 0 beyond the
// support radius, as in the kernel.
double polar_disc_average(const RadialProfile& p, bool transmit, double a, double d) {
  const double inner = p.inner_radius(), S = p.support_radius();
  const auto F = [&](double x) {
    x = std::min(x, S);
    if (!(x > 0.0)) return 0.0;
    return profiles::integrate_log(
        [&](double r) { return r * (transmit ? p.transmittance(r) : p.reflectance(r)); },
        std::min(inner, x), x, 10, 16);
  };
  double sum = 0.0;
  if (d < a) {
    // Every ray leaves the disc once, at ρ(ψ) = −d cos ψ + √(a² − d² sin² ψ) (ψ from the
    // direction away from the centre): smooth in ψ; both half-planes alike.
    sum = 2.0 * gl([&](double psi) {
      const double sn = std::sin(psi);
      return F(-d * std::cos(psi) + std::sqrt(a * a - d * d * sn * sn));
    }, 0.0, kPi, 6);
  } else {
    // Rays towards the centre within ψ_t = asin(a/d) cross the disc between
    // ρ∓ = d cos ψ ∓ √(a² − d² sin² ψ). ψ = ψ_t sin w removes the square root at ψ_t.
    const double psi_t = std::asin(std::min(1.0, a / d));
    sum = 2.0 * gl([&](double w) {
      const double psi = psi_t * std::sin(w);
      const double sn = std::sin(psi);
      const double root = std::sqrt(std::max(0.0, a * a - d * d * sn * sn));
      const double c = d * std::cos(psi);
      return (F(c + root) - F(c - root)) * psi_t * std::cos(w);
    }, 0.0, 0.5 * kPi, 6);
  }
  return sum / (kPi * a * a);
}

// Δf = f'' + f'/r of a radial function by central differences (step 1e-3 r: truncation
// error ~1e-6 relative, rounding ~1e-16/1e-6 = 1e-10).
double radial_laplacian(const RadialProfile& p, double r) {
  const double h = 1e-3 * r;
  const double fp = p.reflectance(r + h), f0 = p.reflectance(r), fm = p.reflectance(r - h);
  return (fp - 2.0 * f0 + fm) / (h * h) + (fp - fm) / (2.0 * h * r);
}

// J0 by the polynomial approximations of Abramowitz & Stegun 9.4.1 (|x| ≤ 3, error
// < 5e-8) and 9.4.3 (x ≥ 3, J0 = f0 cos θ0 / √x, errors < 1.6e-8 and 7e-8):
// std::cyl_bessel_j costs ~1 µs, too slow for the millions of nodes below.
double bessel_j0(double x) {
  x = std::fabs(x);
  if (x <= 3.0) {
    const double y = (x / 3.0) * (x / 3.0);
    return 1.0 + y * (-2.2499997 + y * (1.2656208 + y * (-0.3163866 + y * (0.0444479 +
                 y * (-0.0039444 + y * 0.0002100)))));
  }
  const double y = 3.0 / x;
  const double f0 = 0.79788456 + y * (-0.00000077 + y * (-0.00552740 + y * (-0.00009512 +
                    y * (0.00137237 + y * (-0.00072805 + y * 0.00014476)))));
  const double theta = x - 0.78539816 + y * (-0.04166397 + y * (-0.00003954 + y * (0.00262573 +
                       y * (-0.00054125 + y * (-0.00029333 + y * 0.00013558)))));
  return f0 * std::cos(theta) / std::sqrt(x);
}

// The table of channel c as a function of d (reflect or transmit).
double table(const ScatterKernel& k, bool transmit, int c, double d) {
  return (transmit ? k.transmit(d) : k.reflect(d))[c];
}

// Panels for integrals of K over d: geometric, a 2^(j/2) (K's scales: flat inside
// 0.001 a, the kink at a, the profile's own scales beyond), up to `reach`.
std::vector<double> panel_cuts(const ScatterKernel& k, double reach) {
  const double a = disc_radius(k.point_area());
  std::vector<double> cuts = {0.0};
  for (int j = -20; a * std::pow(2.0, j / 2.0) < reach; ++j) cuts.push_back(a * std::pow(2.0, j / 2.0));
  cuts.push_back(reach);
  return cuts;
}

// The 2D Fourier transform of a radial function, K̂(q) = 2π ∫_0^reach k(d) J0(q d) d dd:
// Gauss–Legendre on panel_cuts, each cut into pieces no wider than a quarter of J0's
// period.
double hankel(const ScatterKernel& k, bool transmit, int c, double q, double reach) {
  const std::vector<double> cuts = panel_cuts(k, reach);
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double width = cuts[i + 1] - cuts[i];
    const int pieces = q > 0.0 ? std::max(1, int(std::ceil(width / (0.5 * kPi / q)))) : 1;
    sum += gl([&](double d) { return table(k, transmit, c, d) * bessel_j0(q * d) * d; },
              cuts[i], cuts[i + 1], pieces);
  }
  return 2.0 * kPi * sum;
}

// ∫ k dA over the plane: K̂(0).
double plane_integral(const ScatterKernel& k, bool transmit, int c) {
  return hankel(k, transmit, c, 0.0, k.support_radius());
}

// The radius beyond which |k| carries less than `fraction` of ∫ |k| dA.
double reach_of(const ScatterKernel& k, bool transmit, int c, double fraction) {
  const std::vector<double> cuts = panel_cuts(k, k.support_radius());
  std::vector<double> mass(cuts.size(), 0.0);  // mass[i]: beyond cuts[i]
  for (std::size_t i = cuts.size() - 1; i-- > 0;)
    mass[i] = mass[i + 1] + 2.0 * kPi * gl([&](double d) {
      return std::fabs(table(k, transmit, c, d)) * d;
    }, cuts[i], cuts[i + 1], 1);
  std::size_t i = 0;
  while (i + 1 < cuts.size() && mass[i] > fraction * mass[0]) ++i;
  return cuts[i];
}

// Poisson summation: for points on the square lattice of spacing s,
//   Σ_n k(|x_o − n s|) s² = Σ_m K̂(2π|m|/s) e^{2πi m·x_o/s},
// so the lattice sum differs from ∫ k dA = K̂(0) by at most Σ_{m≠0} |K̂(2π|m|/s)|.
// K̂ is computed for |m|∞ ≤ 4 (over d up to `reach`, where the mass of |k| left beyond
// is below 1e-9 of the total; that mass bounds the error it makes in each K̂, so it is
// added per term). The rest is bounded by the envelope |K̂| ≤ C |m|^{-5/2} (the disc
// factor 2J1(qa)/(qa) decays like q^{-3/2}, and R̂ at least like 1/q for a 1/r peak), C
// the largest |K̂||m|^{5/2} over 2 ≤ |m| ≤ 4, times 2 for the fit:
//   Σ_{|m|>4} ≤ 2C ∫_4^∞ 2πr r^{-5/2} dr = 2C·4π/√4.
double aliasing_bound(const ScatterKernel& k, bool transmit, int c, double s) {
  const double total = plane_integral(k, transmit, c);
  const double reach = reach_of(k, transmit, c, 1e-9);
  constexpr int kM = 4;
  std::vector<double> at(2 * kM * kM + 1, -1.0);  // |K̂| by |m|²
  double sum = 0.0, envelope = 0.0;
  for (int mx = -kM; mx <= kM; ++mx)
    for (int my = -kM; my <= kM; ++my) {
      const int m2 = mx * mx + my * my;
      if (m2 == 0) continue;
      if (at[m2] < 0.0)
        at[m2] = std::fabs(hankel(k, transmit, c, 2.0 * kPi * std::sqrt(double(m2)) / s, reach)) +
                 1e-9 * std::fabs(total);
      sum += at[m2];
      const double m = std::sqrt(double(m2));
      if (m >= 2.0 && m <= kM) envelope = std::max(envelope, at[m2] * std::pow(m, 2.5));
    }
  return sum + 2.0 * envelope * 4.0 * kPi / std::sqrt(double(kM));
}

// Σ_n k(|x_o − n s|) s² over the lattice of spacing s that covers the support, x_o at a
// generic offset (neither a lattice point nor a cell centre); `point_sampled` sums the
// profile itself at the points within 3 mm instead of the table (beyond, K and R differ
// by < 1e-4 relative: FarFromTheDiscItIsTheProfile; PBD's R costs 4 µs a point).
glm::dvec3 lattice_sum(const ScatterKernel& k, bool transmit, double s,
                       const RgbProfile* point_sampled = nullptr) {
  const double reach = k.support_radius();
  const int n = int(std::ceil(reach / s)) + 1;
  const double ox = 0.3141 * s, oy = 0.2718 * s;
  glm::dvec3 sum(0.0);
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) {
      const double d = std::hypot(i * s - ox, j * s - oy);
      if (point_sampled && d < 3.0) {
        {
          const Rgb r = point_sampled->reflectance(d);
          sum += glm::dvec3(r[0], r[1], r[2]);
        }
      } else {
        sum += transmit ? k.transmit(d) : k.reflect(d);
      }
    }
  return sum * (s * s);
}

}  // namespace

TEST(ScatterKernel, RejectsBadPointArea) {
  const RgbProfile p(Model::BetterDipole, preset("skin1"));
  for (const double area : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity()}) {
    try {
      ScatterKernel k(p, area);
      ADD_FAILURE() << "accepted area " << area;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("point_area_mm2"), std::string::npos) << e.what();
    }
  }
}

TEST(ScatterKernel, MatchesThePolarIntegralOverTheDisc) {
  // The table against the independent polar integral, from d = 0 through the kink at
  // d = a to the tail, for a smooth profile (better dipole), one with a 1/r peak
  // (Burley) and PBD (its 1/r single scattering; 4 µs per R, so one channel and fewer
  // distances), at three point areas (fine, comparable to the mean free path, coarse).
  // Tolerance: the table's contract, 1e-3 relative wherever K > 1e-6 K(0); the polar
  // integral itself is good to ~1e-8 (Gauss–Legendre on smooth integrands). Measured
  // worst: 1.3e-5 (header comment of ScatterKernel.h).
  struct Case {
    Model model;
    int channels;
    std::vector<double> d_over_a;
  };
  const std::vector<double> many = {0.0, 0.01, 0.3, 0.7, 0.95, 0.999, 1.0, 1.001, 1.05,
                                    1.5, 2.0, 3.7, 8.0, 20.0, 60.0, 200.0};
  const std::vector<Case> cases = {{Model::BetterDipole, 3, many},
                                   {Model::Burley, 3, many},
                                   {Model::Pbd, 1, {0.0, 1.0, 1.3}}};
  double worst = 0.0;
  for (const Case& cs : cases) {
    const RgbProfile p(cs.model, preset("skin1"));
    for (const double area : {0.01, 0.25, 4.0}) {
      if (cs.model == Model::Pbd && area != 0.25) continue;
      const ScatterKernel k(p, area);
      const double a = disc_radius(area);
      for (int c = 0; c < cs.channels; ++c) {
        const double k0 = k.reflect(0.0)[c];
        for (const double x : cs.d_over_a) {
          const double d = x * a;
          const double ref = polar_disc_average(p.channel(c), false, a, d);
          if (!(ref > 1e-6 * k0)) continue;
          const double got = k.reflect(d)[c];
          const double rel = std::fabs(got - ref) / ref;
          worst = std::max(worst, rel);
          EXPECT_LT(rel, 1e-3) << profiles::model_name(cs.model) << " area " << area
                               << " channel " << c << " d/a " << x << ": K " << got
                               << " polar " << ref;
        }
      }
    }
  }
  std::printf("[ info ] table vs polar disc integral: worst relative error %.2e\n", worst);
}

TEST(ScatterKernel, DenseScanOfTheTable) {
  // Cubic cells of 1/16 octave: the worst interpolation error lies between nodes, so
  // scan log-spaced distances (not aligned with the cells) from 1e-3 a to the support,
  // every channel: Burley (1/r peak, the harder case) densely, the dipole more sparsely.
  // Tolerance: the 1e-3 contract.
  double worst = 0.0;
  for (const Model model : {Model::BetterDipole, Model::Burley}) {
    const int n = model == Model::Burley ? 120 : 40;
    const RgbProfile p(model, preset("marble"));
    const double area = 0.1;
    const ScatterKernel k(p, area);
    const double a = disc_radius(area);
    for (int c = 0; c < 3; ++c) {
      const double k0 = k.reflect(0.0)[c];
      const double lo = 1e-3 * a, hi = p.support_radius();
      for (int i = 0; i < n; ++i) {
        const double d = lo * std::pow(hi / lo, (i + 0.37) / n);
        const double ref = polar_disc_average(p.channel(c), false, a, d);
        if (!(ref > 1e-6 * k0)) continue;
        const double rel = std::fabs(k.reflect(d)[c] - ref) / ref;
        worst = std::max(worst, rel);
        EXPECT_LT(rel, 1e-3) << profiles::model_name(model) << " channel " << c << " d " << d;
      }
    }
  }
  std::printf("[ info ] dense scan: worst relative error %.2e\n", worst);
}

TEST(ScatterKernel, ZeroBeyondTheSupportAndEvenInD) {
  const RgbProfile p(Model::BetterDipole, preset("skin1"));
  const ScatterKernel k(p, 0.25);
  const double a = disc_radius(0.25);
  EXPECT_DOUBLE_EQ(k.support_radius(), p.support_radius() + a);
  EXPECT_EQ(k.point_area(), 0.25);
  EXPECT_EQ(k.reflect(k.support_radius()), glm::dvec3(0.0));
  EXPECT_EQ(k.reflect(1e9), glm::dvec3(0.0));
  EXPECT_EQ(k.reflect(std::numeric_limits<double>::quiet_NaN()), glm::dvec3(0.0));
  EXPECT_EQ(k.reflect(-0.1), k.reflect(0.1));  // even in d
  // Positive and decreasing in d (R decreases in r, and so does its disc average).
  glm::dvec3 previous = k.reflect(0.0);
  for (double d = 1e-4; d < p.support_radius(); d *= 1.05) {
    const glm::dvec3 v = k.reflect(d);
    for (int c = 0; c < 3; ++c) {
      // Where K < 1e-6 K(0) the table's error is absolute, ~1e-9 K(0): its cubic may dip
      // just below 0 where K reaches 0 at the support.
      EXPECT_GE(v[c], -1e-9 * k.reflect(0.0)[c]) << d;
      // Interpolation may wiggle by the table's 1e-3 where K is flat.
      EXPECT_LE(v[c], previous[c] * (1.0 + 1e-3)) << "d " << d << " channel " << c;
    }
    previous = v;
  }
}

TEST(ScatterKernel, FarFromTheDiscItIsTheProfile) {
  // Mean-value theorem for the disc: the disc average of f minus f at the centre is
  // ∫_0^a (2ρ/a²) (circle mean at ρ − f) dρ, and the circle mean minus f is
  // ∫_0^ρ (t/2) (disc mean of Δf at radius t) dt, so |K(d) − R(d)| ≤ (a²/8) max|ΔR|
  // over the disc. The max is sampled at 9 radii across [d − a, d + a] (ΔR is smooth
  // there, varying by e^{±σ a} < 2 across it), with a factor 1.25 for sampling it; the
  // table adds 1e-3 K.
  for (const Model model : {Model::BetterDipole, Model::Pbd}) {
    const RgbProfile p(model, preset("skin1"));
    const double area = 0.25, a = disc_radius(area);
    const ScatterKernel k(p, area);
    for (int c = 0; c < 3; ++c) {
      for (const double d : {5.0 * a, 10.0 * a, 3.0, 10.0, 30.0}) {
        double lap = 0.0;
        for (int i = 0; i <= 8; ++i)
          lap = std::max(lap, std::fabs(radial_laplacian(p.channel(c), d - a + 2.0 * a * i / 8.0)));
        const double R = p.channel(c).reflectance(d), K = k.reflect(d)[c];
        const double bound = 1.25 * a * a / 8.0 * lap + 1e-3 * K;
        EXPECT_LE(std::fabs(K - R), bound)
            << profiles::model_name(model) << " channel " << c << " d " << d;
        // And the bound is small: a²/d² scaling of a smooth tail, (a/d)² (σd)²/8.
        EXPECT_LT(std::fabs(K - R), 0.05 * R) << "d " << d;
      }
    }
  }
}

TEST(ScatterKernel, IntegralOverThePlaneIsTheTotalReflectance) {
  // The key physics check in its exact form: averaging R over a disc moves light around
  // but keeps all of it, so ∫ K dA = ∫ R dA = the profile's total reflectance (closed
  // form for the dipole and Burley, PBD's own radial quadrature), whatever the point area,
  // including areas far larger than the mean free path. Tolerance: the table's 1e-3
  // (relative, pointwise, so also integrated) + 1e-8 (R beyond the support, Profile.h);
  // the test's quadrature of the piecewise-cubic table adds < 1e-7.
  double worst = 0.0;
  for (const Model model : {Model::BetterDipole, Model::Burley, Model::Pbd}) {
    for (const char* name : {"skin1", "marble"}) {
      const RgbProfile p(model, preset(name));
      const Rgb total = p.total_reflectance();
      for (const double area : {0.01, 4.0}) {
        const ScatterKernel k(p, area);
        for (int c = 0; c < 3; ++c) {
          const double got = plane_integral(k, false, c);
          worst = std::max(worst, std::fabs(got / total[c] - 1.0));
          EXPECT_NEAR(got, total[c], (1e-3 + 1e-8) * total[c])
              << profiles::model_name(model) << " " << name << " area " << area << " channel " << c;
        }
      }
    }
  }
  std::printf("[ info ] ∫K dA vs total reflectance: worst relative error %.2e\n", worst);
}

TEST(ScatterKernel, LatticeOfPointsSumsToTheTotalReflectance) {
  // Points on a square lattice of spacing s (area A = s² each), x_o between them: Σ K A
  // is the total reflectance up to the lattice's aliasing. Tolerance, derived:
  //   Poisson bound on the aliasing (aliasing_bound, computed per case)
  //   + 1e-3 total (the table) + 1e-8 total (R beyond the support).
  // For PBD the bound is loose (Σ|K̂| over the first shells, ~1e-2 at s = 0.1 mm; the
  // phases make the actual error ~10x smaller), for the dipole it is tight.
  struct Case {
    Model model;
    const char* preset;
    double spacing;
  };
  for (const double x : {0.0, 0.7, 2.9, 3.1, 10.0, 123.4})  // the fast J0 the bound uses
    EXPECT_NEAR(bessel_j0(x), std::cyl_bessel_j(0.0, x), 1e-7) << x;
  const std::vector<Case> cases = {{Model::BetterDipole, "skin1", 0.5},
                                   {Model::BetterDipole, "marble", 0.25},
                                   {Model::Pbd, "skin1", 0.1},
                                   {Model::Pbd, "marble", 0.1}};
  for (const Case& cs : cases) {
    const RgbProfile p(cs.model, preset(cs.preset));
    const ScatterKernel k(p, cs.spacing * cs.spacing);
    const glm::dvec3 sum = lattice_sum(k, false, cs.spacing);
    const glm::dvec3 point_sampled = lattice_sum(k, false, cs.spacing, &p);
    const Rgb total = p.total_reflectance();
    for (int c = 0; c < 3; ++c) {
      const double alias = aliasing_bound(k, false, c, cs.spacing);
      EXPECT_NEAR(sum[c], total[c], alias + (1e-3 + 1e-8) * total[c])
          << profiles::model_name(cs.model) << " " << cs.preset << " channel " << c;
      std::printf("[ info ] %s %s s=%.2f channel %d: Σ K A %+.1e, Σ R A %+.1e relative to the "
                  "total (aliasing bound %.1e)\n",
                  std::string(profiles::model_name(cs.model)).c_str(), cs.preset, cs.spacing, c,
                  sum[c] / total[c] - 1.0, point_sampled[c] / total[c] - 1.0, alias / total[c]);
    }
  }
}

TEST(ScatterKernel, SlabTransmitsAndSemiInfiniteDoesNot) {
  // A 3 mm slab of skin1 (multipole): transmit() is the disc average of T (checked
  // against the polar integral of the profile's own T, which also checks the log-log
  // interpolant the kernel reads the multipole through), and it integrates over the plane
  // to the closed-form total transmittance (tolerances as for the reflectance).
  profiles::Medium m = preset("skin1");
  m.thickness_mm = 3.0;
  const RgbProfile slab(Model::Multipole, m);
  const double area = 0.25, a = disc_radius(area);
  const ScatterKernel k(slab, area);
  ASSERT_TRUE(k.has_transmittance());
  const Rgb total_t = slab.total_transmittance(), total_r = slab.total_reflectance();
  const glm::dvec3 lattice = lattice_sum(k, true, std::sqrt(area));
  for (int c = 0; c < 3; ++c) {
    for (const double d : {0.0, a, 3.0}) {
      const double ref = polar_disc_average(slab.channel(c), true, a, d);
      EXPECT_NEAR(k.transmit(d)[c], ref, 1e-3 * std::fabs(ref)) << "channel " << c << " d " << d;
      const double ref_r = polar_disc_average(slab.channel(c), false, a, d);
      EXPECT_NEAR(k.reflect(d)[c], ref_r, 1e-3 * std::fabs(ref_r)) << "channel " << c << " d " << d;
    }
    EXPECT_NEAR(plane_integral(k, true, c), total_t[c], (1e-3 + 1e-8) * total_t[c]) << c;
    EXPECT_NEAR(plane_integral(k, false, c), total_r[c], (1e-3 + 1e-8) * total_r[c]) << c;
    EXPECT_NEAR(lattice[c], total_t[c],
                aliasing_bound(k, true, c, std::sqrt(area)) + (1e-3 + 1e-8) * total_t[c])
        << c;
  }
  // Semi-infinite models have no far face.
  const ScatterKernel bd(RgbProfile(Model::BetterDipole, preset("skin1")), 0.25);
  EXPECT_FALSE(bd.has_transmittance());
  EXPECT_EQ(bd.transmit(0.0), glm::dvec3(0.0));
  EXPECT_EQ(bd.transmit(1.0), glm::dvec3(0.0));
}

TEST(ScatterKernel, ExtremePointAreas) {
  // A point area far below the mean free path (the renderer's floor, 1e-12 mm²) and one
  // far above the support (a = 564 mm): the table still integrates to the total (1e-3,
  // the contract), K is R far from a tiny disc (1e-3 + (a²/8)|ΔR|/R, negligible here),
  // and a disc holding all of R inside gives K(0) = total/(πa²) (R beyond S: 1e-8).
  const RgbProfile p(Model::BetterDipole, preset("skin1"));
  const Rgb total = p.total_reflectance();
  const ScatterKernel tiny(p, 1e-12), huge(p, 1e6);
  const double a = disc_radius(1e6);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(plane_integral(tiny, false, c), total[c], 1e-3 * total[c]) << c;
    EXPECT_NEAR(plane_integral(huge, false, c), total[c], 1e-3 * total[c]) << c;
    for (const double d : {0.01, 1.0, 5.0}) {
      const double R = p.channel(c).reflectance(d);
      EXPECT_NEAR(tiny.reflect(d)[c], R, 1e-3 * R) << "channel " << c << " d " << d;
    }
    EXPECT_NEAR(huge.reflect(0.0)[c], total[c] / (kPi * a * a), (1e-3 + 1e-8) * total[c] / (kPi * a * a));
  }
}

TEST(ScatterKernel, JetIsTheTablesDerivative) {
  // reflect_jet's derivatives are those of the cubic cells: central differences of
  // reflect() with a step of 1e-6 d stay inside one cell (cells are 1/16 octave of
  // |d/a − 1| wide) at these distances, where the cubic is a polynomial evaluated in
  // double: truncation ~(1e-6)² relative, rounding ~1e-16/1e-6; 1e-5 relative covers
  // both with room for points near a cell edge (where the one-sided cell changes).
  // And they are K's own: against central differences (step δ = 0.01 d, truncation
  // ~(σδ)²/6 < 1e-3) of the polar disc integral. A cubic through 4 points of a cell of
  // width h loses one order of accuracy per derivative: with σ = |K'/K| the local decay
  // rate, the error of K' is ~(σh)³/24 and of K'' ~(σh)²/12 relative; tolerance twice
  // that, plus 1% and 3% (measured < 0.1% and < 0.5% where σh is small).
  const RgbProfile p(Model::BetterDipole, preset("skin1"));
  const double area = 0.25, a = disc_radius(area);
  const ScatterKernel k(p, area);
  for (const double d : {0.3 * a, 0.77 * a, 1.6 * a, 3.3, 11.0, 40.0}) {
    const double h = 1e-6 * d;
    const ScatterKernel::Jet j = k.reflect_jet(d);
    const glm::dvec3 kp = k.reflect(d + h), k0 = k.reflect(d), km = k.reflect(d - h);
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(j.value[c], k0[c]);
      const double first = (kp[c] - km[c]) / (2.0 * h);
      EXPECT_NEAR(j.first[c], first, 1e-5 * std::fabs(first) + 1e-9 * k0[c] / a) << d;
      if (d != 3.3 && d != 11.0) continue;
      const double dd = 0.01 * d;
      const double pp = polar_disc_average(p.channel(c), false, a, d + dd);
      const double p0 = polar_disc_average(p.channel(c), false, a, d);
      const double pm = polar_disc_average(p.channel(c), false, a, d - dd);
      const double r1 = (pp - pm) / (2.0 * dd), r2 = (pp - 2.0 * p0 + pm) / (dd * dd);
      const double y = d / a - 1.0;
      const double cell = a * std::exp2(std::floor(std::log2(y))) / 16.0;
      const double sh = std::fabs(r1 / p0) * cell;
      EXPECT_NEAR(j.first[c], r1, (0.01 + sh * sh * sh / 12.0) * std::fabs(r1))
          << "channel " << c << " d " << d;
      EXPECT_NEAR(j.second[c], r2, (0.03 + sh * sh / 6.0) * std::fabs(r2))
          << "channel " << c << " d " << d;
    }
  }
  EXPECT_EQ(k.reflect_jet(k.support_radius() + 1.0).value, glm::dvec3(0.0));
  EXPECT_EQ(k.transmit_jet(1.0).value, glm::dvec3(0.0));  // no transmittance
}

TEST(ScatterKernel, EvaluationCost) {
  // Informational: ns per reflect() call over distances spread like a gather's (log-
  // uniform over the table). No assertion on time (shared machines).
  const ScatterKernel k(RgbProfile(Model::BetterDipole, preset("skin1")), 0.25);
  std::vector<double> d(1 << 16);
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = 1e-3 * std::pow(1e5, double((i * 40503u) % d.size()) / double(d.size()));
  glm::dvec3 acc(0.0);
  const auto t0 = std::chrono::steady_clock::now();
  constexpr int kRounds = 64;
  for (int r = 0; r < kRounds; ++r)
    for (const double x : d) acc += k.reflect(x);
  const double ns = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() /
                    (double(kRounds) * double(d.size()));
  EXPECT_GT(acc.x, 0.0);
  std::printf("[ info ] reflect(): %.1f ns per call\n", ns);
}

