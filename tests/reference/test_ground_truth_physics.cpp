// The random-walk ground truth (reference/GroundTruth.h) against computations that
// share no code with it (issue 16): Chandrasekhar's exact half-space total, mc-table and
// profiles' analog Monte Carlo (its own walk, RNG, HG sampler and Fresnel), and an exact
// energy balance. Every comparison is in standard errors of both sides, plus an accuracy
// goal where the issue states one.
//
// The walk measures what these solve by rendering the builtin:edge slab (200 x 200 x 50 mm)
// with --exitance --diffuse-only: a pixel far from the slab's sides and from the light
// edge sees M = E T(0) R, the flux that leaves per unit area for irradiance E at normal
// incidence, of which T(0) enters (the others count R per unit power entered).
#include "GroundTruthTestSupport.h"

#include "profiles/EdgeResponse.h"
#include "profiles/HFunction.h"
#include "profiles/McTableProfile.h"
#include "profiles/MonteCarlo.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace sss::reference::testing {
namespace {

// Index-matched half-space, isotropic scattering, σt = 1 mm⁻¹ (the slab is 50 mean free
// paths deep: at α = 0.99 the diffusion length is 5.8 mm, so what reaches the bottom is
// below 1e-4 of the total). Goal (issue 16): within 3 standard errors and 0.5% of
// 1 - H(1) √(1 - α). 4 x 2 pixels x 40960 samples give 0.05-0.16% standard error, so
// 3σ stays inside the 0.5% goal.
TEST(GroundTruthPhysics, IndexMatchedHalfSpaceReturnsChandrasekharsTotal) {
  std::uint64_t seed = 7;  // one per albedo: the same numbers would correlate their errors
  for (const double albedo : {0.5, 0.9, 0.99}) {
    const scene::Scene s = edge_slab(grey_medium(1.0 - albedo, albedo, 0.0, 1.0), false);
    const Estimate m = mean_exitance(render_exitance(s, 4, 2, 40960, seed++));
    const double exact = profiles::exact_total_reflectance_index_matched(albedo);
    const double z = (m.mean.x - exact) / m.se.x;
    std::printf("albedo %.2f: walk %.5f +- %.5f, exact %.5f (%+.3f%%, z %+.2f)\n", albedo, m.mean.x, m.se.x, exact,
                100.0 * (m.mean.x / exact - 1.0), z);
    EXPECT_LT(std::abs(z), 3.0) << "albedo " << albedo;
    EXPECT_LT(std::abs(m.mean.x / exact - 1.0), 0.005) << "albedo " << albedo;
    EXPECT_LT(m.se.x / exact, 0.005 / 3.0) << "the test could not resolve its goal";
  }
}

// The analog Monte Carlo's total for one channel, per unit power entered.
profiles::MonteCarloResult analog(const profiles::Coefficients& c, std::uint64_t photons, std::uint64_t seed,
                                  double thickness = std::numeric_limits<double>::infinity()) {
  profiles::MonteCarloOptions o;
  o.photons = photons;
  o.seed = seed;
  o.thickness_mm = thickness;
  return profiles::run_monte_carlo(c, o);
}

// Under a refractive boundary, a fully lit half-space: the walk's M / T(0) against
// mc-table's tabulated total (its stored standard error) and a fresh analog Monte Carlo
// (its per-photon standard error). Skin1 (η 1.3) and skin2 with η 1.5, every channel.
// Pass: within 3 combined standard errors of each, and within 1% (mc-table's own
// documented accuracy is 0.2%; the walk's noise here is 0.1-0.2%).
TEST(GroundTruthPhysics, RefractiveHalfSpaceTotalsMatchMcTableAndTheAnalogWalk) {
  for (const char* preset : {"skin1", "skin2"}) {
    profiles::Medium medium = profiles::preset_medium(*profiles::find_preset(preset));
    if (std::string(preset) == "skin2") medium.eta = {1.5, 1.5, 1.5};
    const scene::Scene s = edge_slab(medium, false);
    const Estimate m = mean_exitance(render_exitance(s, 4, 2, 16384, 11));
    const double t0 = normal_transmission(medium.eta[0]);
    for (int c = 0; c < 3; ++c) {
      const profiles::Coefficients k = medium.channel(c);
      const profiles::McTableProfile table(k);
      const profiles::MonteCarloResult mc = analog(k, 1u << 19, 100 + std::uint64_t(c));
      const double walk = m.mean[c] / t0, walk_se = m.se[c] / t0;
      const double z_table = (walk - table.total_reflectance()) / std::hypot(walk_se, table.total_stderr());
      const double z_mc = (walk - mc.reflectance.total) / std::hypot(walk_se, mc.reflectance.total_stderr);
      std::printf("%s[%s]: walk %.5f +- %.5f, mc-table %.5f +- %.5f (z %+.2f), analog %.5f +- %.5f (z %+.2f)\n",
                  preset, kChannelNames[c], walk, walk_se, table.total_reflectance(), table.total_stderr(), z_table,
                  mc.reflectance.total, mc.reflectance.total_stderr, z_mc);
      EXPECT_LT(std::abs(z_table), 3.0) << preset << " " << kChannelNames[c];
      EXPECT_LT(std::abs(z_mc), 3.0) << preset << " " << kChannelNames[c];
      EXPECT_LT(std::abs(walk / table.total_reflectance() - 1.0), 0.01) << preset << " " << kChannelNames[c];
    }
  }
}

// M(x) of the analog walk's R(r): per annulus its mean R̄ times the exact integral of the
// half-plane weight 2r acos(x/r) over the annulus (antiderivative r² acos(x/r) - x √(r² - x²)).
// Piecewise constant R within 40 annuli per decade: the weight's variation inside an annulus
// is second order (below 1e-4 of M here).
double analog_edge(const profiles::MonteCarloResult& mc, double x) {
  const std::vector<double>& e = mc.bin_edges_mm;
  auto F = [](double r, double a) { return r * r * std::acos(std::min(1.0, a / r)) - a * std::sqrt(std::max(0.0, r * r - a * a)); };
  const double a = std::abs(x);
  double shadow = 0.0;  // flux per unit area at distance a on the dark side
  for (std::size_t k = 0; k + 1 < e.size(); ++k) {
    const double r0 = std::max(e[k], a), r1 = e[k + 1];
    if (r1 <= a) continue;
    shadow += mc.reflectance.value[k] * (F(r1, a) - F(r0, a));
  }
  return x >= 0.0 ? shadow : mc.reflectance.total - shadow;
}

// The light edge under a refractive boundary: M(x) across builtin:edge's edge against
// mc-table's edge response (profiles/EdgeResponse) and the analog walk's, both times T(0).
// 64 columns over 16 mm, 2 rows, 4096 samples per pixel: the walk's noise is 0.5-3% per
// column. The analog side is 8 independent runs of 2^15 photons, its standard error their
// spread; mc-table's is its total's relative standard error (0.05-0.2%). Pass: the
// chi-square over the columns (combined variance) below its 1e-3 upper quantile, per
// channel and reference. Columns where M(x) is under 1% of the total are left out: there
// an eye path reaches the lit side so rarely that 4096 samples are not yet normally
// distributed (their variance is under-estimated, the CLT's condition fails); at 65536
// samples those columns agree too (measured: |z| < 1.3 from 0.25 to 3.75 mm into the
// shadow for skin1's green).
void check_edge(const profiles::Medium& medium, const char* label, bool against_table, std::uint64_t spp = 4096,
                std::uint64_t photons = 1u << 15) {
  constexpr int kW = 64, kH = 2;
  constexpr double kHalf = 8.0;
  const scene::Scene s = edge_slab(medium, true, kHalf);
  const GroundTruthImage img = render_exitance(s, kW, kH, spp, 21);
  const double t0 = normal_transmission(medium.eta[0]);
  for (int c = 0; c < 3; ++c) {
    const profiles::Coefficients k = medium.channel(c);
    const double mfp = 1.0 / k.sigma_t_reduced();
    std::vector<double> edges = profiles::log_bin_edges(1e-3 * mfp, 400.0 * mfp, 220);
    std::vector<std::vector<double>> runs;
    for (int b = 0; b < 8; ++b) {
      profiles::MonteCarloOptions o;
      o.photons = photons;
      o.seed = 1000 + std::uint64_t(b) + 17 * std::uint64_t(c);
      o.bin_edges_mm = edges;
      const profiles::MonteCarloResult mc = profiles::run_monte_carlo(k, o);
      std::vector<double> m(kW);
      for (int x = 0; x < kW; ++x) m[std::size_t(x)] = analog_edge(mc, (x + 0.5) / kW * 2 * kHalf - kHalf);
      runs.push_back(m);
    }
    const profiles::McTableProfile table(k);
    double chi_mc = 0.0, chi_table = 0.0;
    int columns = 0;
    for (int x = 0; x < kW; ++x) {
      const double pos = (x + 0.5) / kW * 2 * kHalf - kHalf;
      if (profiles::edge_response(table, pos) < 0.01 * table.total_reflectance()) continue;
      ++columns;
      double walk = 0.0, var = 0.0;
      for (int y = 0; y < kH; ++y) {
        walk += img.hdr.pixel(x, y)[c] * kPi / (kH * t0);
        var += img.variance.pixel(x, y)[c] * (kPi / (kH * t0)) * (kPi / (kH * t0));
      }
      double mean = 0.0, spread = 0.0;
      for (const auto& r : runs) mean += r[std::size_t(x)] / runs.size();
      for (const auto& r : runs) spread += (r[std::size_t(x)] - mean) * (r[std::size_t(x)] - mean);
      const double mc_var = spread / (runs.size() * (runs.size() - 1));
      chi_mc += (walk - mean) * (walk - mean) / (var + mc_var + 1e-30);
      const double edge = profiles::edge_response(table, pos);
      const double table_se = edge * table.total_stderr() / std::max(table.total_reflectance(), 1e-30);
      chi_table += (walk - edge) * (walk - edge) / (var + table_se * table_se + 1e-30);
      if (c == 1 && x % 8 == 4)
        std::printf("%s x %+6.2f mm: walk %.5f +- %.5f  analog %.5f +- %.5f  mc-table %.5f\n", label, pos, walk,
                    std::sqrt(var), mean, std::sqrt(mc_var), edge);
    }
    const double p_mc = chi_square_upper_tail(chi_mc, columns), p_table = chi_square_upper_tail(chi_table, columns);
    std::printf("%s[%s]: chi2 against the analog walk %.1f (p %.3g), against mc-table %.1f (p %.3g), %d columns\n",
                label, kChannelNames[c], chi_mc, p_mc, chi_table, p_table, columns);
    EXPECT_GE(columns, 32) << label << " " << kChannelNames[c];
    EXPECT_GT(p_mc, 1e-3) << label << " " << kChannelNames[c];
    if (against_table) {
      EXPECT_GT(p_table, 1e-3) << label << " " << kChannelNames[c];
    }
  }
}

TEST(GroundTruthPhysics, LightEdgeUnderARefractiveBoundaryMatchesMcTableAndTheAnalogWalk) {
  check_edge(profiles::preset_medium(*profiles::find_preset("skin1")), "skin1", true);
  profiles::Medium glassy = profiles::preset_medium(*profiles::find_preset("skin2"));
  glassy.eta = {1.5, 1.5, 1.5};
  check_edge(glassy, "skin2 at eta 1.5", true);
}

// Anisotropic scattering: g = 0.8 with the real Henyey–Greenstein phase function, against
// the analog walk's HG mode (mc-table, an isotropic table at the reduced albedo, is not the
// reference here: the similarity relation is exactly what this must not assume). Reduced
// coefficients of skin2 (σs = σs' / 0.2), η 1.3: the total (as above) and the edge.
TEST(GroundTruthPhysics, AnisotropicScatteringMatchesTheAnalogWalksHenyeyGreenstein) {
  profiles::Medium m = profiles::preset_medium(*profiles::find_preset("skin2"));
  for (std::size_t c = 0; c < 3; ++c) {
    m.sigma_s[c] /= 0.2;
    m.g[c] = 0.8;
  }
  const Estimate total = mean_exitance(render_exitance(edge_slab(m, false), 2, 2, 8192, 31));
  const double t0 = normal_transmission(m.eta[0]);
  for (int c = 0; c < 3; ++c) {
    const profiles::MonteCarloResult mc = analog(m.channel(c), 1u << 16, 300 + std::uint64_t(c));
    const profiles::McTableProfile similar(m.channel(c));
    const double walk = total.mean[c] / t0, se = total.se[c] / t0;
    const double z = (walk - mc.reflectance.total) / std::hypot(se, mc.reflectance.total_stderr);
    std::printf("g 0.8 [%s]: walk %.5f +- %.5f, analog HG %.5f +- %.5f (z %+.2f); mc-table by similarity %.5f\n",
                kChannelNames[c], walk, se, mc.reflectance.total, mc.reflectance.total_stderr, z,
                similar.total_reflectance());
    EXPECT_LT(std::abs(z), 3.0) << kChannelNames[c];
  }
  // Its walks are 5x longer (σs 5x): 1024 samples per pixel and 2^13-photon batches keep
  // the analog side's noise at a third of the walk's.
  check_edge(m, "skin2 g 0.8", false, 1024, 1u << 13);
}

// A slab lit from behind: 2 mm of skin2 (η 1.3), 200 x 200 mm, lit at normal incidence
// through its back face (irradiance 1) and seen from the front by an orthographic camera.
// The front's exitance at the centre is E T(0) T_slab, T_slab the analog walk's slab
// transmittance. The slab's sides are 100 mm (50 thicknesses) away: the transmitted flux
// beyond 100 mm is below 1e-9 of T (the analog walk's T(r) tail). Pass: 3 combined
// standard errors per channel.
TEST(GroundTruthPhysics, SlabLitFromBehindTransmitsWhatTheAnalogSlabDoes) {
  const profiles::Medium m = profiles::preset_medium(*profiles::find_preset("skin2"));
  scene::Scene s;
  s.name = "thin slab";
  s.materials.emplace_back();
  s.materials[0].metallic = 0.0f;
  s.materials[0].specular = 0.0f;
  set_medium(s, m);
  const float mm = 1e-3f;
  s.meshes.push_back(scene::make_box({-100 * mm, -100 * mm, -1 * mm}, {100 * mm, 100 * mm, 1 * mm}, 0));
  s.instances.push_back({0, glm::mat4(1.0f), "slab"});
  s.lights.push_back(scene::directional_light("behind", {0.0f, 0.0f, 1.0f}, 1.0f));
  scene::Camera cam;
  cam.projection = scene::Projection::Orthographic;
  cam.xmag = cam.ymag = 5 * mm;
  cam.znear = 10 * mm;
  cam.zfar = 1000 * mm;
  cam.world = scene::look_at_world({0.0f, 0.0f, 100 * mm}, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f});
  s.cameras.push_back(cam);
  const Estimate front = mean_exitance(render_exitance(s, 2, 2, 16384, 41));
  const double t0 = normal_transmission(m.eta[0]);
  for (int c = 0; c < 3; ++c) {
    const profiles::MonteCarloResult mc = analog(m.channel(c), 1u << 20, 400 + std::uint64_t(c), 2.0);
    const double walk = front.mean[c] / t0, se = front.se[c] / t0;
    const double z = (walk - mc.transmittance.total) / std::hypot(se, mc.transmittance.total_stderr);
    std::printf("slab 2 mm [%s]: walk %.5f +- %.5f, analog slab %.5f +- %.5f (z %+.2f)\n", kChannelNames[c], walk, se,
                mc.transmittance.total, mc.transmittance.total_stderr, z);
    EXPECT_LT(std::abs(z), 3.0) << kChannelNames[c];
  }
}

// Energy: a closed sphere (radius 4 mm, 96 x 48 faces) of an index-matched medium with
// σt = 1 mm⁻¹ and albedo 0.9999, lit by a directional light of irradiance 1. What enters
// is E times the mesh's projected area; what leaves is ∫ M dA over the surface, sampled at
// area-uniform points with cosine-distributed exit directions (M = π E[L], plus the light
// that crosses without scattering, 3% of it here). In between,
// the medium absorbs σa⟨ℓ⟩ of it, ⟨ℓ⟩ the mean path length inside: for a non-absorbing
// convex body under uniform isotropic illumination ⟨ℓ⟩ = 4V/S whatever the scattering
// (Blanco & Fournier 2003, the invariance property; Pierrat et al. 2014), and a sphere
// under a directional light is that illumination averaged by symmetry. So the exit
// must be (1 - σa 4V/S) of the entry, 0.9995 here (the second-order term is 1e-7).
// Pass: within 3 standard errors (0.2%; the light that crosses without scattering, if it
// were missing, would show as -3%).
TEST(GroundTruthPhysics, ClosedSphereReturnsWhatEntered) {
  constexpr double kRadiusMm = 4.0, kAlbedo = 0.9999;
  scene::Scene s;
  s.materials.emplace_back();
  s.materials[0].metallic = 0.0f;
  set_medium(s, grey_medium(1.0 - kAlbedo, kAlbedo, 0.0, 1.0));
  s.meshes.push_back(scene::make_uv_sphere(float(kRadiusMm * 1e-3), 96, 48, 0));
  s.instances.push_back({0, glm::mat4(1.0f), "sphere"});
  const glm::dvec3 to_light = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
  s.lights.push_back(scene::directional_light("sun", glm::vec3(-to_light), 1.0f));
  const RayScene rays(s);
  const WalkScene walk(s, rays);
  const WalkMedium& medium = *walk.medium(0);
  // Faces, areas, the entering flux and the volume.
  const scene::Mesh& mesh = s.meshes[0];
  const std::vector<glm::vec3>& p = rays.world_positions(0);
  std::vector<double> cdf;
  double area = 0.0, entered = 0.0, volume = 0.0;
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::dvec3 a = p[mesh.indices[3 * t]], b = p[mesh.indices[3 * t + 1]], c = p[mesh.indices[3 * t + 2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    area += 0.5 * glm::length(n);
    entered += 0.5 * std::max(0.0, glm::dot(n, to_light));
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    cdf.push_back(area);
  }
  constexpr std::uint64_t kSamples = 1u << 19;
  double sum = 0.0, sum2 = 0.0;
  WalkStats stats;
  for (std::uint64_t i = 0; i < kSamples; ++i) {
    walk::WalkRng rng(5, i, 0);
    const double u = rng.uniform() * area;
    const std::uint32_t t = std::uint32_t(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    const glm::dvec3 a = p[mesh.indices[3 * t]], b = p[mesh.indices[3 * t + 1]], c = p[mesh.indices[3 * t + 2]];
    double r1 = rng.uniform(), r2 = rng.uniform();
    if (r1 + r2 > 1.0) {
      r1 = 1.0 - r1;
      r2 = 1.0 - r2;
    }
    const glm::dvec3 x = a + r1 * (b - a) + r2 * (c - a);
    const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));  // outward (CCW from outside)
    glm::dvec3 tt, bb;
    walk::basis(n, tt, bb);
    const double q = rng.uniform(), phi = 2.0 * kPi * rng.uniform();
    const glm::dvec3 out = std::sqrt(q) * (std::cos(phi) * tt + std::sin(phi) * bb) + std::sqrt(1.0 - q) * n;
    const double M = kPi * walk.sample_exitant(medium, x, n, -out, rng, stats).x +
                     walk.unscattered_exitance(medium, x, n).x;
    sum += M;
    sum2 += M * M;
  }
  const double mean = sum / kSamples, var = (sum2 / kSamples - mean * mean) / (kSamples - 1);
  const double exited = area * mean, exited_se = area * std::sqrt(var);
  const double expected = entered * (1.0 - (1.0 - kAlbedo) * 4.0 * volume / area);
  const double z = (exited - expected) / exited_se;
  std::printf("sphere: entered %.4f mm^2, exited %.4f +- %.4f (ratio %.5f, expected %.5f, z %+.2f), "
              "%.1f events per path, %llu escaped\n",
              entered, exited, exited_se, exited / entered, expected / entered, z,
              double(stats.scattering_events) / double(stats.paths), (unsigned long long)stats.escaped);
  EXPECT_LT(std::abs(z), 3.0);
  EXPECT_LT(exited_se / entered, 0.002);
  EXPECT_EQ(stats.escaped, 0u);
}

}  // namespace
}  // namespace sss::reference::testing

