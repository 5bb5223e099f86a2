// The ground-truth renderer as a renderer (issue 16): reproducible for its seed whatever the
// thread count or tiling, stopping at a target error, refusing what it cannot do, warning
// about open meshes, dispersive media, and the statistical regression test against a
// stored ground truth (a per-pixel Z-test, as Mitsuba 3 tests its renders).
#include "GroundTruthTestSupport.h"

#include "reference/TileMerge.h"

#include "profiles/Presets.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#ifndef SSS_SOURCE_DIR
#error "SSS_SOURCE_DIR must name the source folder"
#endif

namespace sss::reference::testing {
namespace {

namespace fs = std::filesystem;

scene::Scene builtin(const char* name) {
  auto loaded = scene::load_scene(name);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) throw std::runtime_error(e->what());
  return std::get<scene::Scene>(std::move(loaded));
}

GroundTruthImage render(const scene::Scene& s, std::uint32_t w, std::uint32_t h, std::uint64_t spp, int threads,
                        TileSpec tile = {}, std::uint64_t seed = 1) {
  GroundTruthOptions o;
  o.width = w;
  o.height = h;
  o.spp = spp;
  o.threads = threads;
  o.tile = tile;
  o.seed = seed;
  return render_ground_truth(s, o);
}

bool same_bits(const image::Image& a, const image::Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)) == 0;
}

TEST(GroundTruthRender, TheImageDependsOnTheSeedAloneNotOnThreadsOrTiles) {
  const scene::Scene s = builtin("builtin:sphere");
  const GroundTruthImage one = render(s, 24, 14, 8, 1), two = render(s, 24, 14, 8, 2);
  EXPECT_TRUE(same_bits(one.hdr, two.hdr));
  EXPECT_TRUE(same_bits(one.variance, two.variance));
  // Three tiles of interleaved rows, put together row by row, are the whole frame.
  image::Image merged(24, 14), merged_var(24, 14);
  for (std::uint32_t k = 1; k <= 3; ++k) {
    const GroundTruthImage t = render(s, 24, 14, 8, 2, {k, 3});
    for (int y = 0; y < 14; ++y) {
      const bool own = std::uint32_t(y) % 3 == k - 1;
      for (int x = 0; x < 24; ++x)
        for (int c = 0; c < 4; ++c) {
          if (own) {
            merged.pixel(x, y)[c] = t.hdr.pixel(x, y)[c];
            merged_var.pixel(x, y)[c] = t.variance.pixel(x, y)[c];
          } else {
            EXPECT_EQ(t.hdr.pixel(x, y)[c], 0.0f) << "tile " << k << " wrote row " << y;
          }
        }
    }
  }
  EXPECT_TRUE(same_bits(merged, one.hdr));
  EXPECT_TRUE(same_bits(merged_var, one.variance));
  // Another seed is another estimate.
  EXPECT_FALSE(same_bits(render(s, 24, 14, 8, 2, {}, 2).hdr, one.hdr));
}

TEST(GroundTruthRender, MergeTilesGivesTheSingleRenderBitForBit) {
  const scene::Scene s = builtin("builtin:sphere");
  const fs::path dir = fs::temp_directory_path() / "sss-ground-truth-merge";
  fs::create_directories(dir);
  const GroundTruthImage whole = render(s, 20, 9, 4, 2);
  std::vector<std::string> files;
  for (std::uint32_t k = 1; k <= 2; ++k) {
    GroundTruthImage t = render(s, 20, 9, 4, 2, {k, 2});
    const std::string tile = std::to_string(k) + "/2";
    t.hdr.attributes = ground_truth_attributes("mean", tile, "test", t.stats.spp, t.stats.relative_standard_error);
    t.variance.attributes = ground_truth_attributes("variance", tile, "test", t.stats.spp, 0.0);
    files.push_back((dir / ("t" + std::to_string(k) + ".exr")).string());
    files.push_back((dir / ("t" + std::to_string(k) + ".var.exr")).string());
    image::write_exr(files[files.size() - 2], t.hdr);
    image::write_exr(files.back(), t.variance);
  }
  auto merged = merge_tiles(files);
  ASSERT_TRUE(std::holds_alternative<MergedFrame>(merged)) << std::get<std::string>(merged);
  const MergedFrame& m = std::get<MergedFrame>(merged);
  EXPECT_TRUE(same_bits(m.mean, whole.hdr));
  EXPECT_TRUE(same_bits(m.variance, whole.variance));
  // Its attributes are a whole render's: no tile, the frame's error recomputed.
  image::Image expected_attributes;
  expected_attributes.attributes = ground_truth_attributes("mean", "", "test", 4, whole.stats.relative_standard_error);
  EXPECT_EQ(m.mean.attributes, expected_attributes.attributes);
  // A tile short: refused, naming it.
  files.pop_back();
  auto short_one = merge_tiles(files);
  ASSERT_TRUE(std::holds_alternative<std::string>(short_one));
  EXPECT_NE(std::get<std::string>(short_one).find("variance tile 2/2 is missing"), std::string::npos)
      << std::get<std::string>(short_one);
  fs::remove_all(dir);
}

TEST(GroundTruthRender, TargetErrorStopsWhenTheFrameIsThatGood) {
  const scene::Scene s = builtin("builtin:sphere");
  GroundTruthOptions o;
  o.width = 16;
  o.height = 9;
  o.target_error = 0.05;
  const GroundTruthImage r = render_ground_truth(s, o);
  EXPECT_LE(r.stats.relative_standard_error, 0.05);
  EXPECT_GT(r.stats.passes, 1);
  EXPECT_DOUBLE_EQ(r.stats.relative_standard_error, relative_standard_error(r.hdr, r.variance));
  // The frame's error falls as 1/√spp: the sample count it stopped at is about what the
  // first pass's noise projected, not a multiple of it (passes grow at most 4x).
  o.target_error = 0.0;
  o.spp = 16;
  const double first = render_ground_truth(s, o).stats.relative_standard_error;
  const double projected = 16.0 * (first / 0.05) * (first / 0.05);
  EXPECT_GT(double(r.stats.spp), 0.5 * projected);
  EXPECT_LT(double(r.stats.spp), 2.0 * projected);
  // --spp caps it.
  o.target_error = 1e-4;
  o.spp = 32;
  EXPECT_EQ(render_ground_truth(s, o).stats.spp, 32u);
}

TEST(GroundTruthRender, RefusesWhatItCannotDoNamingTheOption) {
  const scene::Scene s = builtin("builtin:sphere");
  struct Case {
    GroundTruthOptions o;
    const char* field;
  };
  auto with = [](auto change) {
    GroundTruthOptions o;
    o.width = 8;
    o.height = 8;
    o.spp = 4;
    change(o);
    return o;
  };
  const Case cases[] = {
      {with([](GroundTruthOptions& o) { o.spp = 0; }), "spp"},
      {with([](GroundTruthOptions& o) { o.target_error = -1; }), "target error"},
      {with([](GroundTruthOptions& o) { o.target_error = std::nan(""); }), "target error"},
      {with([](GroundTruthOptions& o) { o.target_error = 0.1, o.spp = 1; }), "spp"},
      {with([](GroundTruthOptions& o) { o.tile = {0, 2}; }), "tile"},
      {with([](GroundTruthOptions& o) { o.tile = {3, 2}; }), "tile"},
      {with([](GroundTruthOptions& o) { o.tile = {1, 9}; }), "tile"},
      {with([](GroundTruthOptions& o) { o.tile = {1, 2}, o.target_error = 0.1; }), "tile"},
      {with([](GroundTruthOptions& o) { o.width = 0; }), "width"},
      {with([](GroundTruthOptions& o) { o.threads = -1; }), "threads"},
  };
  for (const Case& c : cases) {
    try {
      render_ground_truth(s, c.o);
      ADD_FAILURE() << "accepted, expected an error naming " << c.field;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(c.field, 0), 0u) << e.what();
    }
  }
  std::string why;
  EXPECT_FALSE(parse_tile("2/", why));
  EXPECT_FALSE(parse_tile("-1/3", why));
  EXPECT_FALSE(parse_tile("4/3", why));
  EXPECT_TRUE(parse_tile("3/3", why));
}

// A mesh with a hole: the warning names it and says what a hole does; the render still
// runs (nothing escapes into the void unaccounted: escaped walks are counted).
TEST(GroundTruthRender, AnOpenMeshIsNamedAndItsHolesExplained) {
  scene::Scene s = builtin("builtin:sphere");
  scene::Mesh& m = s.meshes[0];
  m.name = "leaky sphere";
  m.indices.resize(m.indices.size() - 3 * (96 + 3 * 192));  // the last four rings: a cap at the south pole
  s.cameras[0] = scene::frame_bounds(s.bounds(), {0.0f, 1.0f, -0.3f});     // seen from below
  GroundTruthOptions o;
  o.width = 16;
  o.height = 9;
  o.spp = 16;
  std::vector<std::string> warned;
  o.on_warning = [&](const std::string& w) { warned.push_back(w); };
  const GroundTruthImage r = render_ground_truth(s, o);
  ASSERT_EQ(warned.size(), 1u);
  EXPECT_EQ(warned, r.stats.warnings);
  EXPECT_NE(warned[0].find("'leaky sphere'"), std::string::npos) << warned[0];
  EXPECT_NE(warned[0].find("holes"), std::string::npos) << warned[0];
  EXPECT_NE(warned[0].find("darker"), std::string::npos) << warned[0];
  EXPECT_NE(warned[0].find("lost"), std::string::npos) << warned[0];
  EXPECT_GT(r.stats.walk.escaped, 0u);
  // The closed sphere warns of nothing.
  o.on_warning = {};
  EXPECT_TRUE(render_ground_truth(builtin("builtin:sphere"), o).stats.warnings.empty());
}

// A dispersive medium (η per channel) walks each index separately: its red and green,
// at η 1.3, are the η = 1.3 medium's red and green; its blue at 1.5 the η = 1.5 one's.
// Frame totals compared in standard errors.
TEST(GroundTruthRender, ADispersiveMediumWalksEachIndexOnItsOwn) {
  profiles::Medium m = profiles::preset_medium(*profiles::find_preset("skin1"));
  auto total = [&](const Rgb& eta, std::uint64_t seed) {
    scene::Scene s = builtin("builtin:sphere");
    profiles::Medium d = m;
    d.eta = eta;
    set_medium(s, d);
    GroundTruthOptions o;
    o.width = 16;
    o.height = 9;
    o.spp = 256;
    o.seed = seed;
    o.diffuse_only = true;
    const GroundTruthImage r = render_ground_truth(s, o);
    Estimate e;
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 16; ++x)
        for (int c = 0; c < 3; ++c) {
          e.mean[c] += r.hdr.pixel(x, y)[c];
          e.se[c] += r.variance.pixel(x, y)[c];
        }
    e.se = glm::sqrt(e.se);
    return e;
  };
  const Estimate mixed = total({1.3, 1.3, 1.5}, 1), low = total({1.3, 1.3, 1.3}, 2), high = total({1.5, 1.5, 1.5}, 3);
  for (int c = 0; c < 3; ++c) {
    const Estimate& same = c < 2 ? low : high;
    const double z = (mixed.mean[c] - same.mean[c]) / std::hypot(mixed.se[c], same.se[c]);
    EXPECT_LT(std::abs(z), 4.0) << kChannelNames[c];
  }
  // And the index matters enough to be seen: 1.3 against 1.5 in blue.
  EXPECT_GT(std::abs(low.mean.z - high.mean.z) / std::hypot(low.se.z, high.se.z), 4.0);
}

// The statistical regression test (Mitsuba 3's test_renders.py): a fresh 1024-sample render
// of builtin:sphere at 32 x 18 with another seed against the stored ground truth
// (tests/golden/ground-truth/zsphere: 16384 samples, its variance beside it). Per pixel and
// channel z = (fresh - stored) / sqrt(var_fresh + var_stored), two-sided p-values, and a
// Šidák correction over all of them for a family-wise false-alarm rate of 1e-3: any change
// to the walk that moves a pixel's expectation by a few of its standard errors fails,
// without a tolerance to tune.
TEST(GroundTruthRender, AFreshRenderAgreesWithTheStoredGroundTruthPixelByPixel) {
  const std::string base = std::string(SSS_SOURCE_DIR) + "/tests/golden/ground-truth/zsphere";
  auto stored = image::read_image(base + ".exr"), stored_var = image::read_image(base + ".var.exr");
  ASSERT_TRUE(std::holds_alternative<image::Image>(stored) && std::holds_alternative<image::Image>(stored_var))
      << base << ".exr: run tests/golden/ground-truth/render.sh";
  const image::Image& ref = std::get<image::Image>(stored);
  const image::Image& ref_var = std::get<image::Image>(stored_var);
  const std::uint64_t stored_spp = std::stoull(attribute(ref, kAttrSpp).value_or("0"));
  ASSERT_GT(stored_spp, 1000u);
  constexpr std::uint64_t kFreshSpp = 1024;
  const GroundTruthImage fresh = render(builtin("builtin:sphere"), std::uint32_t(ref.width), std::uint32_t(ref.height),
                                        kFreshSpp, 0, {}, 20261201);
  int tests = 0, exact = 0, skipped = 0;
  double worst_p = 1.0, chi = 0.0, worst_p_shifted = 1.0;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x) {
      ASSERT_EQ(fresh.hdr.pixel(x, y)[3], ref.pixel(x, y)[3]) << "geometry differs at " << x << ", " << y;
      for (int c = 0; c < 3; ++c) {
        const double a = fresh.hdr.pixel(x, y)[c], b = ref.pixel(x, y)[c];
        // The fresh mean's variance from the stored per-sample variance (16384 samples,
        // precise), as Mitsuba 3 does: the fresh render's own estimate comes from the same
        // samples as its mean, and for skewed samples a low mean comes with a low variance
        // estimate, which would inflate |z|.
        const double per_sample = double(ref_var.pixel(x, y)[c]) * double(stored_spp);
        const double var = per_sample / double(kFreshSpp) + ref_var.pixel(x, y)[c];
        if (var == 0.0) {  // deterministic pixels (background, opaque): equal, bit for bit
          EXPECT_EQ(a, b) << x << ", " << y;
          ++exact;
          continue;
        }
        // Pixels the walk reaches the light from only rarely (the far side, the shadow)
        // have heavy-tailed samples: their means are not yet normal and their variance
        // estimates run low, so a Z-test would flag noise, not change. Only channel-pixels
        // whose stored estimate is within 1% (a per-sample relative deviation below 1.3
        // over its 16384 samples) are tested; the choice uses the stored side alone.
        if (!(std::sqrt(double(ref_var.pixel(x, y)[c])) <= 0.01 * b)) {
          ++skipped;
          continue;
        }
        const double z = (a - b) / std::sqrt(var);
        chi += z * z;
        const double p = std::erfc(std::abs(z) / std::sqrt(2.0));
        worst_p = std::min(worst_p, p);
        // The test's power: the same render against a stored truth 3% brighter must fail.
        worst_p_shifted = std::min(worst_p_shifted, std::erfc(std::abs(a - 1.03 * b) / std::sqrt(var) / std::sqrt(2.0)));
        ++tests;
      }
    }
  const double alpha = 1.0 - std::pow(1.0 - 1e-3, 1.0 / tests);
  std::printf("Z-test: %d channel-pixels (%d exact, %d too noisy to test), smallest p %.3g (Sidak threshold %.3g), "
              "mean z^2 %.3f\n",
              tests, exact, skipped, worst_p, alpha, chi / tests);
  EXPECT_GT(tests, 100);
  EXPECT_GT(worst_p, alpha);
  EXPECT_LT(worst_p_shifted, alpha) << "a 3% change would go unnoticed";
  // The z scores are standard normal as a whole too: mean z² within 4 standard errors of 1.
  // A pixel's three channels come from the same walks and move together, so the standard
  // error of mean z² is sqrt(2 / pixels), not sqrt(2 / channel-pixels) (measured: two fresh
  // 16384-sample renders against each other give mean z² 1.02-1.22 over these pixels).
  EXPECT_LT(std::abs(chi / tests - 1.0), 4.0 * std::sqrt(2.0 / (tests / 3.0)));
}

}  // namespace
}  // namespace sss::reference::testing
namespace sss::reference::testing {
namespace {
// What a hole costs (reference/README.md, "Holes"): builtin:sphere (30 mm skin1)
// with a cap of its four last rings cut out around the pole that faces the light and the
// camera, against the closed sphere, red channel, by distance from the hole's rim in the
// image (head-on there, so about the distance on the surface).
//   test_reference --gtest_also_run_disabled_tests --gtest_filter='*WhatAHoleCosts'
TEST(GroundTruthStudy, DISABLED_WhatAHoleCosts) {
  scene::Scene closed = builtin("builtin:sphere");
  closed.cameras[0] = scene::frame_bounds(closed.bounds(), {0.0f, 1.0f, -0.3f});
  closed.lights[0] = scene::directional_light("from below", {0.0f, 1.0f, -0.3f}, 3.0f);
  scene::Scene open = closed;
  open.meshes[0].indices.resize(open.meshes[0].indices.size() - 3 * (96 + 3 * 192));
  GroundTruthOptions o;
  o.width = 48;
  o.height = 27;
  o.spp = 4096;
  o.diffuse_only = true;
  const GroundTruthImage a = render_ground_truth(closed, o);
  o.seed = 2;  // independent of the closed render
  const GroundTruthImage b = render_ground_truth(open, o);
  // The sphere's and the hole's centres and radii in the image.
  double gx = 0, gy = 0, gn = 0, hx = 0, hy = 0, hn = 0;
  for (int y = 0; y < int(o.height); ++y)
    for (int x = 0; x < int(o.width); ++x) {
      if (!(a.hdr.pixel(x, y)[3] > 0.5f)) continue;
      gx += x, gy += y, ++gn;
      if (b.hdr.pixel(x, y)[0] < 1e-4f && a.hdr.pixel(x, y)[0] > 0.01f) hx += x, hy += y, ++hn;
    }
  ASSERT_GT(hn, 10.0);
  const double mm_per_px = 30.0 / std::sqrt(gn / kPi), hole_r = std::sqrt(hn / kPi);
  hx /= hn, hy /= hn;
  std::printf("hole radius %.1f mm in the image; escaped walks %.1f%%\n", hole_r * mm_per_px,
              100.0 * double(b.stats.walk.escaped) / double(b.stats.walk.paths));
  for (int ring = 0; ring < 12; ++ring) {  // rings 2 mm wide
    glm::dvec3 sa(0.0), sb(0.0), va(0.0), vb(0.0);
    for (int y = 0; y < int(o.height); ++y)
      for (int x = 0; x < int(o.width); ++x) {
        const double d = (std::hypot(x - hx, y - hy) - hole_r) * mm_per_px;
        if (d < 2.0 * ring || d >= 2.0 * ring + 2.0 || !(a.hdr.pixel(x, y)[0] > 0.01f) || !(b.hdr.pixel(x, y)[0] > 0.0f))
          continue;
        for (int c = 0; c < 3; ++c) {
          sa[c] += a.hdr.pixel(x, y)[c], sb[c] += b.hdr.pixel(x, y)[c];
          va[c] += a.variance.pixel(x, y)[c], vb[c] += b.variance.pixel(x, y)[c];
        }
      }
    if (!(sa.x > 0)) continue;
    std::printf("%2d-%2d mm from the rim: open / closed", 2 * ring, 2 * ring + 2);
    for (int c = 0; c < 3; ++c)
      std::printf("  %s %.3f +- %.3f", kChannelNames[c], sb[c] / sa[c],
                  sb[c] / sa[c] * std::hypot(std::sqrt(va[c]) / sa[c], std::sqrt(vb[c]) / sb[c]));
    std::printf("\n");
  }
}
}  // namespace
}  // namespace sss::reference::testing
