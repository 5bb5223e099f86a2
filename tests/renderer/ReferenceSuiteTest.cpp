// The physics half of the golden-frame suite (issue 4): every real-time mode against the
// CPU reference (reference), scene by scene, at small sizes on lavapipe.
//
// For each case the GPU frame and the reference image (linear radiance, EXR-equivalent)
// are compared with image::compare over the pixels where both have geometry; the case
// fails when its relative RMSE exceeds the limit in tests/golden/reference/tolerances.json,
// where each limit sits beside the value measured when it was set and the reason that
// mode deviates from the exact answer. On failure the GPU frame, the reference and an
// error heat map are written to golden-out/.
//
// Every run writes golden-out/REPORT.md (every metric for every scene x mode x model,
// and the time of each); tests/golden/bless.sh (SSS_BLESS=1) also refreshes the measured
// values in tolerances.json and writes tests/golden/REPORT.md, the accuracy statement the
// README links.
//
// SSS_SUITE_SWITCHES="fresnel=on single-scattering=off" (either or both, on or off)
// renders the GPU frames and the references with those switches instead of the defaults:
// how each default was measured against the ground truth (README "Directional Fresnel",
// "Single scattering"). The limits are for the defaults, so expect failures with others.
//
// All cases run in one test so that the report is one table (ctest runs each test in its
// own process).
#include "RenderTest.h"

#include "MaterialOverrides.h"

#include "image/HeatMap.h"
#include "image/Metrics.h"
#include "reference/GroundTruth.h"
#include "reference/ReferenceRenderer.h"
#include "scene/BuiltinScenes.h"

#include "profiles/Profile.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#ifdef SSS_SOURCE_DIR

namespace sss::renderer::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(SSS_SOURCE_DIR) / "tests" / "golden";

// The suite's reference density: 1 reduced mean free path between irradiance points.
// The disc-averaged kernel keeps that within ~1% of converged on smooth lighting
// (tests/reference/test_reference_edge.cpp measures the edge at 0.5 and 1 mfp), far below
// every real-time mode's deviation here.
constexpr double kReferenceSpacingMfp = 1.0;

struct SuiteCase {
  const char* scene;
  SssTechnique technique;
  const char* model;  // nullptr: the scene's own
  std::uint32_t width, height;
  std::uint32_t texture_size = 0;  // texture space's atlas size
};

SuiteCase texture_case(const char* scene, std::uint32_t w, std::uint32_t h, std::uint32_t size,
                       const char* model = nullptr) {
  return {scene, SssTechnique::Texture, model, w, h, size};
}

std::string kind_name(const SuiteCase& c) {
  return std::string(technique_name(c.technique));
}

std::string short_scene(const std::string& scene) {
  if (scene.rfind("builtin:", 0) == 0) return scene.substr(8);
  return fs::path(scene).stem().string();
}

std::string case_key(const SuiteCase& c, const std::string& model) {
  return short_scene(c.scene) + "/" + kind_name(c) + "/" + model;
}

scene::Scene load(const std::string& name, const char* model) {
  auto loaded = scene::load_scene(name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) throw std::runtime_error(e->what());
  scene::Scene s = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(s);
  scene::add_light_if_missing(s);
  if (model) {  // as sss-viewer --model / sss-reference --model do it
    app::MaterialOverrideArgs args;
    args.model = model;
    auto changed = app::apply_material_overrides(s, args);
    if (auto* e = std::get_if<FieldError>(&changed)) throw std::runtime_error(e->what());
  }
  return s;
}

std::string model_of(const scene::Scene& s) {
  std::string out;
  for (const scene::Material& m : s.materials)
    if (m.sss.enabled) {
      const std::string name(profiles::model_name(m.sss.model));
      if (out.find(name) == std::string::npos) out += (out.empty() ? "" : "+") + name;
    }
  return out.empty() ? "none" : out;
}

// The error budget (DESIGN.md §1), GPU frame minus ground truth split into six links,
// each the difference of two images that differ in one approximation:
//   1 model        diffusion reference (exact R, ray-traced shadows) - ground truth
//   2 fit          reference with the GPU's Gaussian fit - diffusion reference
//   3 lighting     reference with the fit, lit by the GPU's shadow maps - reference with the fit
//   4 transmission that, with the GPU's transmission rule (the far side dark, E T(d) / R_d at
//                  points facing away from a light, d ray-cast: --transmission local) - that
//                  with the profile's own (the far side's points summed)
//   5 thickness    that, with d read from the shadow map as the GPU reads it - d ray-cast
//   6 blur         GPU frame - the reference with the fit, the shadow maps and the GPU's
//                  transmission and thickness (the real-time blur, fp16 targets)
// The differences telescope: link 1 + ... + 6 = GPU - truth, pixel for pixel. Each is
// a relative RMSE over the same pixels, normalised by the truth's signal (its noise
// taken off); bias is the signed Σ difference / Σ truth, which adds up exactly.
constexpr int kLinks = 6;
struct Links {
  double rmse[kLinks] = {}, bias[kLinks] = {};
  double total = 0.0, total_bias = 0.0;  // GPU - truth
};

struct Row {
  std::string key, scene, mode, model;
  std::uint32_t width = 0, height = 0;
  image::Metrics m;
  // Against the stored ground truth (tests/golden/ground-truth): the diffusion reference
  // and the GPU frame, each with the ground truth's own noise subtracted (Metrics.h).
  bool has_truth = false;
  double reference_vs_truth = 0.0, gpu_vs_truth = 0.0, truth_noise = 0.0;
  Links whole, scattered;  // the budget of the whole radiance, and of the scattered light alone
  // (every image less its specular; the truth's specular is the diffusion reference's, the
  // same code on the same ray)
  bool has_budget = false;
  // The GPU frame against the diffusion reference on the scattered light (issue 17's bunny goal).
  double gpu_vs_reference_scattered = 0.0;
  // The limit, derived (tests/golden/reference/tolerances.json, "_comment"): by the triangle
  // inequality ‖G − D‖ ≤ ‖F − D‖ + ‖S − F‖ + ‖L − S‖ + ‖M − L‖ + ‖G − M‖ (D reference, F
  // with the fit, S also lit by the shadow maps, L also with the GPU's transmission rule,
  // M also with the shadow map's thickness, G the frame; relative to ‖D‖ over the compared
  // pixels). The fit, lighting, transmission and thickness links are CPU renders, computed
  // in every run; the blur link is the GPU's, bounded by
  // the value stored at bless plus 3 q, q the reference's own quadrature noise (S rendered
  // with another seed of its point sets: what the reference cannot resolve).
  double fit_d = 0.0, lit_d = 0.0, trans_d = 0.0, thick_d = 0.0, blur_d = 0.0, quadrature = 0.0, blur_bound = 0.0;
  double limit = 0.0;
  bool pass = false;
  double gpu_ms = 0.0, reference_ms = 0.0;
  std::size_t points = 0;
};

std::string fixed(double v, int digits) {
  if (std::isinf(v)) return "inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

struct Truth {
  image::Image mean, variance;
  nlohmann::json summary;
};

// Σ over the pixels of `mask` (alpha > kGeometryAlpha in every image given) of (a - b)²
// and of (a - b), over R, G, B.
struct DiffSums {
  double squares = 0.0, sum = 0.0;
};
DiffSums difference(const image::Image& a, const image::Image& b, const std::vector<std::uint8_t>& mask) {
  DiffSums d;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double e = double(a.rgba[4 * i + c]) - double(b.rgba[4 * i + c]);
      d.squares += e * e;
      d.sum += e;
    }
  }
  return d;
}

// The six links of the chain truth -> reference -> with the fit -> lit by the shadow maps
// -> with the GPU's transmission rule -> with its thickness -> GPU over `mask` (Links above). `noise` is Σ over the mask of the truth's variance of
// the mean: E[Σ T²] = Σ T_true² + noise and E[Σ(x - T)²] = Σ(x - T_true)² + noise, so it is
// taken off the signal, link 1 and the total. Nullopt when the truth has no signal there.
std::optional<Links> budget_links(const image::Image& truth, double noise, const image::Image& reference,
                                  const image::Image& fit, const image::Image& lit, const image::Image& local,
                                  const image::Image& local_map, const image::Image& gpu,
                                  const std::vector<std::uint8_t>& mask) {
  double signal = -noise, truth_sum = 0.0;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i])
      for (int ch = 0; ch < 3; ++ch) {
        signal += double(truth.rgba[4 * i + ch]) * truth.rgba[4 * i + ch];
        truth_sum += truth.rgba[4 * i + ch];
      }
  if (!(signal > 0.0 && truth_sum > 0.0)) return std::nullopt;
  const image::Image* chain[kLinks + 1] = {&truth, &reference, &fit, &lit, &local, &local_map, &gpu};
  Links l;
  for (int k = 0; k < kLinks; ++k) {
    const DiffSums d = difference(*chain[k + 1], *chain[k], mask);
    l.rmse[k] = std::sqrt((k == 0 ? std::max(0.0, d.squares - noise) : d.squares) / signal);
    l.bias[k] = d.sum / truth_sum;
  }
  const DiffSums total = difference(gpu, truth, mask);
  l.total = std::sqrt(std::max(0.0, total.squares - noise) / signal);
  l.total_bias = total.sum / truth_sum;
  return l;
}


void write_report(const fs::path& path, const std::vector<Row>& rows, const nlohmann::json& tolerances,
                  const std::map<std::string, Truth>& truths) {
  std::ostringstream md;
  md << "# Real-time frames against the CPU reference\n\n"
        "Written by `ReferenceSuiteTest` (tests/renderer/ReferenceSuiteTest.cpp); refresh with\n"
        "`tests/golden/bless.sh`. Each row renders one scene with one real-time mode on lavapipe\n"
        "and compares it with the CPU reference (reference: Embree rays, irradiance\n"
        "points "
     << kReferenceSpacingMfp
     << " reduced mean free path apart, the Jensen–Buhler octree, the exact profile of\n"
        "the model, no Gaussian fit), pixel for pixel, over the pixels where both images have\n"
        "geometry, silhouette pixels left out. Linear radiance; SSIM on the tonemapped images.\n\n"
        "Metrics (image/Metrics.h): relative RMSE = √(Σ(a−b)²/Σb²), PSNR against the\n"
        "reference's peak, max abs error in radiance units, `>5%` = fraction of pixels whose\n"
        "error exceeds 5% of the peak, SSIM (Wang et al. 2004). *limit* is the test's bound on\n"
        "the relative RMSE, derived from the error budget (\"How each limit is derived\" below;\n"
        "tests/golden/reference/tolerances.json holds the blur link's stored bound and why each mode deviates). Times: GPU = lavapipe frame (CPU Vulkan, sum of the pass timestamps),\n"
        "reference = whole CPU render, both on this machine's cores in the same run.\n\n"
        "The last two columns measure both against **true light transport**: the stored ground truth\n"
        "of the scene (`sss-reference --method random-walk`, a volumetric random walk through the\n"
        "scene's own meshes with the materials' real σa, σs, g and η behind a smooth dielectric;\n"
        "tests/golden/ground-truth, made by its render.sh), as relative RMSE with the ground\n"
        "truth's own noise subtracted (image/Metrics.h; the ground truth's noise is in\n"
        "the table below). *reference vs truth* is the diffusion reference's distance from it (the\n"
        "flat semi-infinite diffusion profile applied to this geometry, the Lambertian exit, the\n"
        "missing Fresnel factors); *GPU vs truth* the real-time frame's. Every image renders with the\n"
        "defaults: single scattering on (issue 18: S(1) per pixel, profiles without their own once-scattered\n"
        "light; README \"Single scattering\"), directional Fresnel off (README \"Directional Fresnel\").\n\n"
        "| scene | mode | model | size | rel. RMSE | limit | RMSE | PSNR dB | max abs | >5% | SSIM | GPU ms | reference ms | reference / GPU | reference vs truth | GPU vs truth |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows)
    md << "| " << r.scene << " | " << r.mode << " | " << r.model << " | " << r.width << "×" << r.height
       << " | " << fixed(100.0 * r.m.relative_rmse, 2) << "% | " << fixed(100.0 * r.limit, 2) << "%"
       << (r.pass ? "" : " **FAIL**") << " | " << fixed(r.m.rmse, 5) << " | " << fixed(r.m.psnr_db, 1)
       << " | " << fixed(r.m.max_abs_error, 4) << " | " << fixed(100.0 * r.m.fraction_over_threshold, 1)
       << "% | " << fixed(r.m.ssim, 4) << " | " << fixed(r.gpu_ms, 1) << " | " << fixed(r.reference_ms, 0)
       << " | " << fixed(r.reference_ms / std::max(r.gpu_ms, 1e-3), 0) << "× | "
       << (r.has_truth ? fixed(100.0 * r.reference_vs_truth, 1) + "%" : "—") << " | "
       << (r.has_truth ? fixed(100.0 * r.gpu_vs_truth, 1) + "%" : "—") << " |\n";
  md << "\n## The error budget\n\n"
        "Each frame's distance from the ground truth, split into six links, each measured by switching one\n"
        "approximation (DESIGN.md §1): **1 model** = diffusion reference − ground truth (the flat\n"
        "semi-infinite profile on this geometry, similarity, no directional or single-scattering terms);\n"
        "**2 fit** = the reference summing the GPU's Gaussian fit (`sss-reference --kernel fit`) − the\n"
        "reference; **3 lighting** = that, lit by the GPU's shadow maps and PCF rebuilt on the CPU\n"
        "(`--shadows shadow-map --shadow-map-size 512`) − the reference with the fit; **4 transmission** =\n"
        "that with the GPU's transmission rule (`--transmission local`: the far side's points dark, and each\n"
        "point facing away from a light gets E (−n·l) T(d) / R_d, T the fit's tail beyond the thickness d,\n"
        "ray-cast) − that with the profile's own (the far side's points summed with R or a slab's T);\n"
        "**5 thickness** = that with d read from the light's shadow map as the GPU reads it\n"
        "(`--thickness-from shadow-map`) − d ray-cast; **6 blur** = the GPU frame − the reference with the fit,\n"
        "the shadow maps and the GPU's transmission and thickness (the real-time blur, fp16 targets).\n"
        "Each is a relative RMSE over the\n"
        "same pixels (silhouettes left out), divided by the ground truth's signal with its noise taken off;\n"
        "in brackets the bias, Σ difference / Σ truth. The six differences add up to GPU − truth pixel\n"
        "for pixel, so the biases add up exactly; the RMSEs add in quadrature plus the links' cross terms:\n"
        "*left over* = total² − Σ link² (signed square root; positive where links push the same way).\n\n"
        "| scene | mode | model | 1 model | 2 fit | 3 lighting | 4 transmission | 5 thickness | 6 blur | √Σ link² | GPU vs truth | left over | truth noise |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto pct = [](double v) { return fixed(100.0 * v, 1) + "%"; };
  auto link_cell = [&](double rmse, double bias) {
    return pct(rmse) + " (" + (bias >= 0.0 ? "+" : "") + fixed(100.0 * bias, 1) + "%)";
  };
  for (const Row& r : rows) {
    if (!r.has_budget) continue;
    double quad = 0.0;
    for (double l : r.whole.rmse) quad += l * l;
    const double left = r.whole.total * r.whole.total - quad;
    md << "| " << r.scene << " | " << r.mode << " | " << r.model;
    for (int k = 0; k < kLinks; ++k) md << " | " << link_cell(r.whole.rmse[k], r.whole.bias[k]);
    md << " | " << pct(std::sqrt(quad)) << " | " << link_cell(r.whole.total, r.whole.total_bias) << " | "
       << (left >= 0.0 ? "+" : "−") << pct(std::sqrt(std::fabs(left))) << " | " << pct(r.truth_noise) << " |\n";
  }
  md << "\n### The scattered light alone\n\n"
        "The same links with every image's specular taken off (the GPU's specular target, the references'\n"
        "specular term; the truth's specular is the diffusion reference's, the same code on the same ray):\n"
        "what subsurface scattering itself gets wrong. *GPU vs reference* is the frame against the\n"
        "diffusion reference (exact profile, ray-traced shadows) on the scattered light, relative RMSE.\n\n"
        "| scene | mode | model | 1 model | 2 fit | 3 lighting | 4 transmission | 5 thickness | 6 blur | GPU vs truth | GPU vs reference |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    if (!r.has_budget) continue;
    md << "| " << r.scene << " | " << r.mode << " | " << r.model;
    for (int k = 0; k < kLinks; ++k) md << " | " << pct(r.scattered.rmse[k]);
    md << " | " << link_cell(r.scattered.total, r.scattered.total_bias) << " | " << pct(r.gpu_vs_reference_scattered)
       << " |\n";
  }
  md << "\n## The ground truths\n\n"
        "| scene | size | samples per pixel | relative standard error | time | made |\n|---|---|---|---|---|---|\n";
  for (const auto& [name, t] : truths)
    md << "| " << name << " | " << t.mean.width << "×" << t.mean.height << " | " << t.summary.value("spp", 0) << " | "
       << fixed(100.0 * t.summary.value("relative_standard_error", 0.0), 2) << "% | "
       << fixed(t.summary.value("seconds", 0.0), 0) << " s on " << t.summary.value("threads", 0) << " threads | "
       << t.summary.value("date", std::string("?")).substr(0, 10) << ", " << t.summary.value("commit", std::string("?"))
       << " |\n";
  md << "\nEach is `tests/golden/ground-truth/NAME.exr` (mean) with `NAME.var.exr` (the variance of each\n"
        "pixel's mean) and `NAME.json` (the exact command, samples, error, time, machine and commit).\n";
  md << "\n## Screen space or texture space\n\n"
        "Compare each scene's *texture* row with its *separable* and *gaussians* rows.\n\n"
        "- **Texture space wins on accuracy on curved objects** (the sphere, the bunny): it\n"
        "  blurs along the surface in mm of surface (the stretch map), where the screen path\n"
        "  blurs in the image, scaled by the surface's slope along each blur direction and\n"
        "  weighted by depth from the tangent plane: in creases, across depth steps and at\n"
        "  the last pixels of a silhouette the screen kernel mixes what the surface does not,\n"
        "  and it hides what lies behind a silhouette. On flat parts (edge, slab, tile)\n"
        "  it equals the exact per-Gaussian blur (the gaussians row). It does not depend on the\n"
        "  view: no undersampling when the object is small on screen.\n"
        "- **The screen path wins where there is no good atlas and on cost when lights move**:\n"
        "  it needs no UVs, so it has no parameterization artifacts (the bunny's generated\n"
        "  atlas leaves one faint lighter strip on the flank in texture space, renderer/README.md\n"
        "  \"Texture space\"); and its blur costs the pixels covered, the texture path's the\n"
        "  texels of every object, visible or not (bench/texture_space.sh on lavapipe: 0.11 s\n"
        "  per update at 256², 1.7 s at 1024², against 0.08 s for the screen separable blur at\n"
        "  1280×720).\n"
        "- **With lights and materials still, texture space is cheaper** (`--texture-update\n"
        "  on-change`): the atlas is reused while the camera moves, and the frame costs one more\n"
        "  raster of the objects (the lookup) instead of a screen blur.\n";
  md << "\n## How each limit is derived\n\n"
        "The limit on a row's relative RMSE against the reference is the sum of its links' bounds (the\n"
        "triangle inequality ‖G − D‖ ≤ ‖F − D‖ + ‖S − F‖ + ‖L − S‖ + ‖M − L‖ + ‖G − M‖, all relative to the\n"
        "reference D over the compared pixels): the fit, lighting, transmission and thickness links are CPU\n"
        "renders, computed in every run; the blur link (the GPU frame G against M, the reference with the fit,\n"
        "the shadow maps and the GPU's transmission and thickness) is bounded by the value\n"
        "stored at bless (`blur_link` in tests/golden/reference/tolerances.json) plus 3 q, where q is the\n"
        "reference's own quadrature noise (S rendered again with another seed of its irradiance points;\n"
        "q = ‖S − S'‖/√2): a change of the frame smaller than that cannot be told from the reference's\n"
        "sampling. Both the blur bound and the limit are asserted.\n\n"
        "| scene | mode | model | fit (computed) | lighting (computed) | transmission (computed) | thickness (computed) | blur (stored) | 3 q | limit | measured total | blur now |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows)
    md << "| " << r.scene << " | " << r.mode << " | " << r.model << " | " << fixed(100.0 * r.fit_d, 2) << "% | "
       << fixed(100.0 * r.lit_d, 2) << "% | " << fixed(100.0 * r.trans_d, 2) << "% | "
       << fixed(100.0 * r.thick_d, 2) << "% | "
       << fixed(100.0 * (r.blur_bound - 3.0 * r.quadrature), 2) << "% | "
       << fixed(300.0 * r.quadrature, 2) << "% | " << fixed(100.0 * r.limit, 2) << "% | "
       << fixed(100.0 * r.m.relative_rmse, 2) << "% | " << fixed(100.0 * r.blur_d, 2) << "% |\n";
  md << "\n## Why each mode deviates\n\n";
  for (auto it = tolerances.begin(); it != tolerances.end(); ++it) {
    if (it.key().rfind("_", 0) == 0) continue;
    md << "- **" << it.key() << "**: " << it.value().value("why", std::string("(not written)")) << "\n";
  }
  std::ofstream f(path);
  f << md.str();
}

class ReferenceSuiteTest : public RenderTest {};

TEST_F(ReferenceSuiteTest, EveryRealTimeModeAgainstTheCpuReference) {
  const std::string textured = (fs::path(SSS_SOURCE_DIR) / "assets" / "textured_tile.glb").string();
  // nullptr: the scene's own model, i.e. profiles::kDefaultModel (mc-table) everywhere but
  // the slab (multipole). better-dipole, the default until issue 8, keeps explicit rows on
  // the edge and the sphere in every mode so that it stays covered.
  const std::vector<SuiteCase> cases = {
      {"builtin:edge", SssTechnique::Separable, nullptr, 128, 16},
      {"builtin:edge", SssTechnique::Gaussians, nullptr, 128, 16},
      {"builtin:edge", SssTechnique::Separable, "better-dipole", 128, 16},
      {"builtin:edge", SssTechnique::Gaussians, "better-dipole", 128, 16},
      {"builtin:sphere", SssTechnique::Separable, nullptr, 160, 90},
      {"builtin:sphere", SssTechnique::Gaussians, nullptr, 160, 90},
      {"builtin:sphere", SssTechnique::Separable, "better-dipole", 160, 90},
      {"builtin:sphere", SssTechnique::Gaussians, "better-dipole", 160, 90},
      {"builtin:sphere", SssTechnique::Separable, "pbd", 160, 90},
      {"builtin:sphere", SssTechnique::Gaussians, "pbd", 160, 90},
      {"builtin:sphere", SssTechnique::Gaussians, "dipole", 160, 90},
      {"builtin:bunny", SssTechnique::Separable, nullptr, 160, 90},
      {"builtin:bunny", SssTechnique::Gaussians, nullptr, 160, 90},
      {"builtin:slab", SssTechnique::Separable, nullptr, 160, 90},
      {"builtin:slab", SssTechnique::Gaussians, nullptr, 160, 90},
      {"builtin:materials", SssTechnique::Separable, nullptr, 240, 135},
      {"builtin:materials", SssTechnique::Gaussians, nullptr, 240, 135},
      {textured.c_str(), SssTechnique::Separable, nullptr, 160, 90},
      {textured.c_str(), SssTechnique::Gaussians, nullptr, 160, 90},
      // Texture space (issue 6): 512^2 atlases (the materials' 15 spheres at 256^2).
      texture_case("builtin:edge", 128, 16, 512),
      texture_case("builtin:edge", 128, 16, 512, "better-dipole"),
      texture_case("builtin:sphere", 160, 90, 512),
      texture_case("builtin:sphere", 160, 90, 512, "better-dipole"),
      texture_case("builtin:bunny", 160, 90, 512),
      texture_case("builtin:slab", 160, 90, 512),
      texture_case("builtin:materials", 240, 135, 256),
      texture_case(textured.c_str(), 160, 90, 512),
  };
  const bool bless = std::getenv("SSS_BLESS") != nullptr;
  const std::string switches = std::getenv("SSS_SUITE_SWITCHES") ? std::getenv("SSS_SUITE_SWITCHES") : "";
  auto setting = [&](const std::string& name, bool fallback) {
    if (switches.find(name + "=on") != std::string::npos) return true;
    if (switches.find(name + "=off") != std::string::npos) return false;
    return fallback;
  };
  const bool fresnel = setting("fresnel", RenderOptions{}.fresnel);
  const bool single = setting("single-scattering", RenderOptions{}.single_scattering);
  const fs::path tolerance_path = kGoldenDir / "reference" / "tolerances.json";
  nlohmann::json tolerances = nlohmann::json::object();
  {
    std::ifstream f(tolerance_path);
    if (f) tolerances = nlohmann::json::parse(f);
    else ASSERT_TRUE(bless) << "missing " << tolerance_path << ": run tests/golden/bless.sh";
  }
  const fs::path out = fs::current_path() / "golden-out";
  fs::create_directories(out);

  // The references of one scene + model + size: the diffusion reference (D), the budget's
  // intermediate ones (F: the GPU's Gaussian fit summed, link 2; S: that lit by the GPU's
  // shadow maps at the suite's 512², link 3; L: that with the GPU's transmission rule,
  // link 4; M: that with the shadow map's thickness, link 5), and S with another seed of
  // the irradiance points (its difference from S is the reference's quadrature noise).
  struct References {
    reference::ReferenceImage exact, fit, lit, local, local_map, lit_seed2;
  };
  std::map<std::string, References> references;
  // The stored ground truths, by short scene name: read, never rendered here.
  std::map<std::string, Truth> truths;
  for (const SuiteCase& c : cases) {
    const std::string name = short_scene(c.scene);
    if (truths.count(name)) continue;
    const fs::path base = kGoldenDir / "ground-truth" / name;
    auto mean = image::read_image(base.string() + ".exr");
    auto var = image::read_image(base.string() + ".var.exr");
    ASSERT_TRUE(std::holds_alternative<image::Image>(mean) && std::holds_alternative<image::Image>(var))
        << base << ".exr / .var.exr: missing or unreadable; tests/golden/ground-truth/render.sh makes them";
    Truth t{std::get<image::Image>(mean), std::get<image::Image>(var), {}};
    std::ifstream summary(base.string() + ".json");
    ASSERT_TRUE(summary) << base << ".json missing";
    t.summary = nlohmann::json::parse(summary);
    ASSERT_EQ(t.mean.width, int(c.width)) << name << ": the ground truth is not at the suite's size";
    ASSERT_EQ(t.mean.height, int(c.height)) << name << ": the ground truth is not at the suite's size";
    // Issue 16: every stored ground truth reaches 1% relative standard error or better,
    // and the variance stored beside it says so.
    EXPECT_LE(t.summary.value("relative_standard_error", 1.0), 0.01) << name;
    EXPECT_NEAR(reference::relative_standard_error(t.mean, t.variance), t.summary.value("relative_standard_error", 1.0),
                1e-6)
        << name << ": the variance file does not belong to the mean";
    truths[name] = std::move(t);
  }
  // x against the ground truth, over the pixels both have geometry in (silhouettes of the
  // suite's mask left out), the truth's noise subtracted.
  auto against_truth = [](const image::Image& x, const Truth& t, const image::Image& mask) {
    image::Image a = x, b = t.mean;
    for (std::size_t i = 3; i < a.rgba.size(); i += 4)
      if (!(mask.rgba[i] > image::kGeometryAlpha)) a.rgba[i] = b.rgba[i] = 0.0f;
    image::CompareOptions co;
    co.encoding = image::Encoding::Linear;
    co.reference_variance = &t.variance;
    return image::compare(a, b, co);
  };
  std::vector<Row> rows;
  for (const SuiteCase& c : cases) {
    const scene::Scene s = load(c.scene, c.model);
    Row row;
    row.scene = short_scene(c.scene);
    row.mode = kind_name(c);
    row.model = model_of(s);
    row.key = case_key(c, row.model);
    row.width = c.width;
    row.height = c.height;
    SCOPED_TRACE(row.key);

    const std::string ref_key = std::string(c.scene) + "|" + row.model + "|" + std::to_string(c.width) +
                                "x" + std::to_string(c.height);
    if (!references.count(ref_key)) {
      References& r = references[ref_key];
      reference::ReferenceOptions ro;
      ro.width = c.width;
      ro.height = c.height;
      ro.spacing_mfp = kReferenceSpacingMfp;
      ro.fresnel = fresnel;
      ro.single_scattering = single;
      r.exact = reference::render_reference(s, ro);
      ro.kernel = reference::KernelSource::Fit;
      r.fit = reference::render_reference(s, ro);
      ro.shadows = reference::Shadows::ShadowMap;
      ro.shadow_map_size = small_options(c.width, c.height).shadow_map_size;
      r.lit = reference::render_reference(s, ro);
      ro.transmission = reference::Transmission::Local;
      r.local = reference::render_reference(s, ro);
      ro.thickness = reference::Thickness::ShadowMap;
      r.local_map = reference::render_reference(s, ro);
      ro.thickness = reference::Thickness::RayCast;
      ro.transmission = reference::Transmission::Profile;
      ro.seed = 2;
      r.lit_seed2 = reference::render_reference(s, ro);
    }
    const References& refs = references[ref_key];
    const reference::ReferenceImage& ref = refs.exact;
    row.reference_ms = ref.stats.total_ms;
    row.points = ref.stats.points;

    RenderOptions options = small_options(c.width, c.height, c.technique);
    options.fresnel = fresnel;
    options.single_scattering = single;
    if (c.technique == SssTechnique::Texture) options.texture_size = c.texture_size;
    const Frame f = render(s, options, 3);
    row.gpu_ms = f.stats.gpu_ms;
    image::CompareOptions co;
    co.encoding = image::Encoding::Linear;
    image::Image gpu_hdr = f.hdr, ref_hdr = ref.hdr;
    // Silhouettes left out (image::exclude_silhouettes says why), as sss-compare
    // --exclude-silhouettes does.
    image::exclude_silhouettes(gpu_hdr, ref_hdr);
    row.m = image::compare(gpu_hdr, ref_hdr, co);
    if (auto t = truths.find(row.scene); t != truths.end()) {
      const image::Metrics r = against_truth(ref.hdr, t->second, gpu_hdr), g = against_truth(f.hdr, t->second, gpu_hdr);
      row.has_truth = true;
      row.reference_vs_truth = r.relative_rmse_noise_subtracted;
      row.gpu_vs_truth = g.relative_rmse_noise_subtracted;
      row.truth_noise = r.reference_noise;
      // The budget, over the compared pixels that every image of the chain covers.
      const Truth& truth = t->second;
      const image::Image& fit = refs.fit.hdr;
      const image::Image& lit = refs.lit.hdr;
      const image::Image& local = refs.local.hdr;
      const image::Image& local_map = refs.local_map.hdr;
      std::vector<std::uint8_t> mask(std::size_t(c.width) * c.height, 0);
      double noise = 0.0;
      for (std::size_t i = 0; i < mask.size(); ++i) {
        bool on = true;
        for (const image::Image* im : std::initializer_list<const image::Image*>{&gpu_hdr, &truth.mean, &ref.hdr, &fit, &lit, &local, &local_map})
          on = on && im->rgba[4 * i + 3] > image::kGeometryAlpha;
        mask[i] = on;
        if (on)
          for (int ch = 0; ch < 3; ++ch) noise += truth.variance.rgba[4 * i + ch];
      }
      if (const auto whole = budget_links(truth.mean, noise, ref.hdr, fit, lit, local, local_map, gpu_hdr, mask)) {
        row.whole = *whole;
        row.has_budget = true;
        const image::Image d_sc = image::subtract_rgb(ref.hdr, ref.specular);
        const image::Image g_sc = image::subtract_rgb(gpu_hdr, f.specular);
        if (const auto sc = budget_links(image::subtract_rgb(truth.mean, ref.specular), noise, d_sc,
                                         image::subtract_rgb(fit, refs.fit.specular),
                                         image::subtract_rgb(lit, refs.lit.specular),
                                         image::subtract_rgb(local, refs.local.specular),
                                         image::subtract_rgb(local_map, refs.local_map.specular), g_sc, mask))
          row.scattered = *sc;
        double ref_sc = 0.0;
        for (std::size_t i = 0; i < mask.size(); ++i)
          if (mask[i])
            for (int ch = 0; ch < 3; ++ch) ref_sc += double(d_sc.rgba[4 * i + ch]) * d_sc.rgba[4 * i + ch];
        if (ref_sc > 0.0) row.gpu_vs_reference_scattered = std::sqrt(difference(g_sc, d_sc, mask).squares / ref_sc);
      }
    }

    {
      // The derived limit's parts over the compared pixels (gpu_hdr's mask), relative to the reference.
      const image::Image& fit = refs.fit.hdr;
      const image::Image& lit = refs.lit.hdr;
      const image::Image& local = refs.local.hdr;
      const image::Image& local_map = refs.local_map.hdr;
      const image::Image& lit2 = refs.lit_seed2.hdr;
      std::vector<std::uint8_t> cmp(std::size_t(c.width) * c.height, 0);
      double ref_sq = 0.0;
      for (std::size_t i = 0; i < cmp.size(); ++i) {
        cmp[i] = gpu_hdr.rgba[4 * i + 3] > image::kGeometryAlpha && ref_hdr.rgba[4 * i + 3] > image::kGeometryAlpha;
        if (cmp[i])
          for (int ch = 0; ch < 3; ++ch) ref_sq += double(ref.hdr.rgba[4 * i + ch]) * ref.hdr.rgba[4 * i + ch];
      }
      ASSERT_GT(ref_sq, 0.0);
      row.fit_d = std::sqrt(difference(fit, ref.hdr, cmp).squares / ref_sq);
      row.lit_d = std::sqrt(difference(lit, fit, cmp).squares / ref_sq);
      row.trans_d = std::sqrt(difference(local, lit, cmp).squares / ref_sq);
      row.thick_d = std::sqrt(difference(local_map, local, cmp).squares / ref_sq);
      row.blur_d = std::sqrt(difference(f.hdr, local_map, cmp).squares / ref_sq);
      row.quadrature = std::sqrt(difference(lit, lit2, cmp).squares / 2.0 / ref_sq);
    }
    if (bless) {
      nlohmann::json& t = tolerances[row.key];
      t["measured_relative_rmse"] = std::round(row.m.relative_rmse * 1e4) / 1e4;
      t["blur_link"] = std::ceil(row.blur_d * 1e4) / 1e4;  // rounded up: the bound holds at bless
      t.erase("limit_relative_rmse");
      if (!t.contains("why")) t["why"] = "(to be written: measured at bless time)";
    }
    ASSERT_TRUE(tolerances.contains(row.key)) << "no tolerance for " << row.key << " in " << tolerance_path;
    ASSERT_TRUE(tolerances[row.key].contains("blur_link")) << row.key << ": no blur_link in " << tolerance_path
                                                           << " (run tests/golden/bless.sh)";
    row.blur_bound = tolerances[row.key].at("blur_link").get<double>() + 3.0 * row.quadrature;
    row.limit = row.fit_d + row.lit_d + row.trans_d + row.thick_d + row.blur_bound;
    row.pass = row.m.relative_rmse <= row.limit && row.blur_d <= row.blur_bound;
    EXPECT_LE(row.blur_d, row.blur_bound)
        << row.key << ": the GPU's blur link (frame against the reference with the fit, the shadow maps and the GPU's "
        << "transmission and thickness) is "
        << row.blur_d << ", beyond the " << tolerances[row.key].at("blur_link").get<double>()
        << " stored at bless plus 3x the reference's quadrature noise " << row.quadrature << "; GPU, reference and "
        << "heat map written to " << out;
    // Implied by the blur bound through the triangle inequality when the links are measured
    // on the metric's own pixels and normalisation: this checks that bookkeeping.
    EXPECT_LE(row.m.relative_rmse, row.limit)
        << row.key << ": relative RMSE " << row.m.relative_rmse << " against the reference exceeds the derived limit "
        << row.limit << " (fit " << row.fit_d << " + lighting " << row.lit_d << " + transmission " << row.trans_d << " + thickness " << row.thick_d
        << " + blur bound " << row.blur_bound
        << "; measured " << tolerances[row.key].value("measured_relative_rmse", -1.0) << " at bless)";
    std::printf("[ %-36s ] rel RMSE %6.2f%% (limit %5.1f%%) SSIM %.4f  GPU %.1f ms  reference %.0f ms (%zu points)"
                "  vs truth: reference %.1f%%, GPU %.1f%%  budget: model %.1f%% fit %.1f%% lighting %.1f%% "
                "transmission %.1f%% thickness %.1f%% blur %.1f%% (total %.1f%%); scattered light: %.1f%% %.1f%% "
                "%.1f%% %.1f%% %.1f%% %.1f%% (total %.1f%%, GPU vs reference %.1f%%)\n",
                row.key.c_str(), 100.0 * row.m.relative_rmse, 100.0 * row.limit, row.m.ssim, row.gpu_ms,
                row.reference_ms, row.points, 100.0 * row.reference_vs_truth, 100.0 * row.gpu_vs_truth,
                100.0 * row.whole.rmse[0], 100.0 * row.whole.rmse[1], 100.0 * row.whole.rmse[2],
                100.0 * row.whole.rmse[3], 100.0 * row.whole.rmse[4], 100.0 * row.whole.rmse[5],
                100.0 * row.whole.total, 100.0 * row.scattered.rmse[0], 100.0 * row.scattered.rmse[1],
                100.0 * row.scattered.rmse[2], 100.0 * row.scattered.rmse[3], 100.0 * row.scattered.rmse[4],
                100.0 * row.scattered.rmse[5], 100.0 * row.scattered.total,
                100.0 * row.gpu_vs_reference_scattered);
    if (!row.pass || bless) {
      std::string file = row.key;
      for (char& ch : file)
        if (ch == '/') ch = '_';
      image::write_png((out / (file + ".gpu.png")).string(), f.display);
      image::write_png((out / (file + ".reference.png")).string(), ref.display);
      const std::vector<float> err = image::pixel_errors(gpu_hdr, ref_hdr);
      image::write_png((out / (file + ".diff.png")).string(),
                       image::render_heatmap(err, image::geometry_mask(gpu_hdr, ref_hdr), f.hdr.width,
                                             f.hdr.height, std::max(row.m.max_abs_error, 1e-6)));
    }
    rows.push_back(row);
  }
  write_report(out / "REPORT.md", rows, tolerances, truths);
  if (bless) {
    std::ofstream(tolerance_path) << tolerances.dump(2) << "\n";
    write_report(kGoldenDir / "REPORT.md", rows, tolerances, truths);
  }
}

// Issue 18 part 2: S = S_d + S(1) against true transport. On builtin:edge and
// builtin:sphere (the suite's sizes, the stored ground truths), the diffusion reference
// and the GPU frame (separable) with single scattering on must be closer to the ground
// truth than with it off, significantly: with D = Σ (on - t)² - Σ (off - t)² over the
// pixels all four images cover (silhouettes left out, as the suite does), the truth's
// noise enters D only through -2 Σ (on - off) δt, whose standard deviation is
// 2 sqrt(Σ (on - off)² var_t) from the stored per-pixel variance; both renders are
// deterministic. The test asks D < -4 SD (a one-sided Z-test at 4σ: 3e-5 false-alarm
// rate per comparison over the 4 here). It also prints both relative RMSEs.
TEST_F(ReferenceSuiteTest, SingleScatteringBringsEdgeAndSphereCloserToTheGroundTruth) {
  struct Case {
    const char* scene;
    std::uint32_t width, height;
  };
  for (const Case& c : {Case{"builtin:edge", 128, 16}, Case{"builtin:sphere", 160, 90}}) {
    const scene::Scene s = load(c.scene, nullptr);
    const fs::path base = kGoldenDir / "ground-truth" / short_scene(c.scene);
    auto mean = image::read_image(base.string() + ".exr");
    auto var = image::read_image(base.string() + ".var.exr");
    ASSERT_TRUE(std::holds_alternative<image::Image>(mean) && std::holds_alternative<image::Image>(var)) << base;
    const image::Image& truth = std::get<image::Image>(mean);
    const image::Image& variance = std::get<image::Image>(var);
    ASSERT_EQ(truth.width, int(c.width));
    image::Image on[2], off[2];  // [0] diffusion reference, [1] GPU
    for (const bool single : {false, true}) {
      reference::ReferenceOptions ro;
      ro.width = c.width;
      ro.height = c.height;
      ro.spacing_mfp = kReferenceSpacingMfp;
      ro.single_scattering = single;
      (single ? on : off)[0] = reference::render_reference(s, ro).hdr;
      RenderOptions options = small_options(c.width, c.height, SssTechnique::Separable);
      options.single_scattering = single;
      (single ? on : off)[1] = render(s, options).hdr;
    }
    // The suite's pixels: geometry in every image, the GPU frame's silhouettes left out.
    image::Image masked = off[1], other = on[1];
    image::exclude_silhouettes(masked, other);
    for (int k = 0; k < 2; ++k) {
      double d = 0.0, var_d = 0.0, sq_on = 0.0, sq_off = 0.0, signal = 0.0;
      for (std::size_t i = 0; i < truth.rgba.size() / 4; ++i) {
        bool in = masked.rgba[4 * i + 3] > image::kGeometryAlpha && truth.rgba[4 * i + 3] > image::kGeometryAlpha;
        for (const image::Image* im : {&on[0], &on[1], &off[0], &off[1]})
          in = in && im->rgba[4 * i + 3] > image::kGeometryAlpha;
        if (!in) continue;
        for (int ch = 0; ch < 3; ++ch) {
          const double t = truth.rgba[4 * i + ch], a = on[k].rgba[4 * i + ch], b = off[k].rgba[4 * i + ch];
          d += (a - t) * (a - t) - (b - t) * (b - t);
          var_d += 4.0 * (a - b) * (a - b) * variance.rgba[4 * i + ch];
          sq_on += (a - t) * (a - t);
          sq_off += (b - t) * (b - t);
          signal += t * t;
        }
      }
      ASSERT_GT(signal, 0.0);
      const double sd = std::sqrt(var_d);
      const char* who = k == 0 ? "diffusion reference" : "GPU separable";
      std::printf("[ %s %s vs truth: S(1) off %.2f%%, on %.2f%% rel. RMSE; D = %.3g, SD %.3g (z = %.1f) ]\n",
                  short_scene(c.scene).c_str(), who, 100.0 * std::sqrt(sq_off / signal),
                  100.0 * std::sqrt(sq_on / signal), d, sd, d / sd);
      EXPECT_LT(d, -4.0 * sd) << c.scene << " " << who;
    }
  }
}

}  // namespace
}  // namespace sss::renderer::testing

#endif  // SSS_SOURCE_DIR
