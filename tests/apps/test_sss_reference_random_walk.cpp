// sss-reference --method random-walk and `sss-reference merge` (issue 16): the documented
// options, the EXR header attributes, the variance and the JSON summary; bad input exits
// 2 naming the option and writes nothing; tiles (also spread by GNU parallel, as the
// README shows) merge into files byte-identical to one process's render, whatever the
// thread count; merge refuses tile sets that do not fit; Ctrl-C leaves no file.
// Every render is tiny (builtin:sphere at 24x12 or smaller): each test is well under 5 s.
#ifdef SSS_REFERENCE_EXE

#include "common/CliRun.h"
#include "image/Image.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

using sss::testing::CliRun;
using sss::testing::slurp;

fs::path scratch() {
  static const fs::path dir = sss::testing::scratch_dir("sss-reference-walk-test");
  return dir;
}

// An empty folder of the test's own under scratch(), so that "writes nothing" means it.
fs::path folder(const std::string& name) {
  const fs::path d = scratch() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

CliRun reference(const std::string& args) {
  return sss::testing::run_cli(SSS_REFERENCE_EXE, args, scratch() / "stderr.txt");
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

std::optional<std::string> attribute(const sss::image::Image& image, const std::string& name) {
  for (const auto& [key, value] : image.attributes)
    if (key == name) return value;
  return std::nullopt;
}

sss::image::Image read(const fs::path& path) {
  auto r = sss::image::read_image(path.string());
  if (auto* e = std::get_if<sss::image::ImageError>(&r)) {
    ADD_FAILURE() << e->what();
    return {};
  }
  return std::get<sss::image::Image>(std::move(r));
}

// The frame every tile test renders: small, a fixed sample count and seed.
const std::string kFrame = "builtin:sphere --method random-walk --width 24 --height 12 --spp 16 --seed 3 --quiet";

// Renders kFrame (plus `extra`) whole into dir/whole.exr and dir/whole.var.exr.
void render_whole(const fs::path& dir, const std::string& extra = "") {
  const CliRun r = reference(kFrame + " --out " + (dir / "whole.exr").string() + " --variance " +
                             (dir / "whole.var.exr").string() + " " + extra);
  ASSERT_EQ(r.code, 0) << r.err;
}

// Renders tile k/3 of kFrame (plus `extra`) into dir/tK.exr and dir/tK.var.exr.
void render_tile(const fs::path& dir, int k, const std::string& extra = "") {
  const std::string t = "t" + std::to_string(k);
  const CliRun r = reference(kFrame + " --tile " + std::to_string(k) + "/3 --out " + (dir / (t + ".exr")).string() +
                             " --variance " + (dir / (t + ".var.exr")).string() + " " + extra);
  ASSERT_EQ(r.code, 0) << r.err;
}

std::string files(const fs::path& dir, const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += " " + (dir / n).string();
  return s;
}

TEST(SssReferenceRandomWalk, HelpListsTheWalkOptions) {
  const CliRun r = reference("--help");
  EXPECT_EQ(r.code, 0) << r.err;
  for (const char* opt : {"--method", "--spp", "--target-error", "--variance", "--tile", "--exitance", "--summary"})
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  EXPECT_NE(r.out.find("random-walk"), std::string::npos);
  const CliRun m = reference("merge --help");
  EXPECT_EQ(m.code, 0) << m.err;
  for (const char* opt : {"--out", "--variance"}) EXPECT_NE(m.out.find(opt), std::string::npos) << opt;
}

// --environment through the CLI: the walk takes it (the furnace test in
// tests/reference checks its value); every geometry pixel gains light, the background
// stays 0, and a bad value is refused by name with nothing written.
TEST(SssReferenceRandomWalk, TakesAnEnvironmentLight) {
  const fs::path dir = folder("environment");
  const CliRun plain = reference(kFrame + " --out " + (dir / "plain.exr").string());
  ASSERT_EQ(plain.code, 0) << plain.err;
  const CliRun sky = reference(kFrame + " --environment 0.5,0.5,0.5 --out " + (dir / "sky.exr").string());
  ASSERT_EQ(sky.code, 0) << sky.err;
  const sss::image::Image a = read(dir / "plain.exr"), b = read(dir / "sky.exr");
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  int lit = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (a.pixel(x, y)[3] <= 0.0f) {
        EXPECT_EQ(b.pixel(x, y)[0], 0.0f);
        continue;
      }
      ++lit;
      EXPECT_GT(b.pixel(x, y)[0], a.pixel(x, y)[0]) << x << "," << y;
    }
  EXPECT_GT(lit, 20);
  const CliRun bad = reference(kFrame + " --environment 1,1 --out " + (dir / "bad.exr").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--environment"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "bad.exr"));
}

TEST(SssReferenceRandomWalk, WritesMeanVarianceAndSummaryWithTheirAttributes) {
  const fs::path dir = folder("small");
  const fs::path exr = dir / "sphere.exr", var = dir / "sphere.var.exr", json = dir / "sphere.json";
  const CliRun r = reference("builtin:sphere --method random-walk --width 16 --height 9 --spp 8 --quiet --out " +
                             exr.string() + " --variance " + var.string() + " --summary " + json.string());
  ASSERT_EQ(r.code, 0) << r.err;

  const sss::image::Image mean = read(exr), variance = read(var);
  EXPECT_EQ(mean.width, 16);
  EXPECT_EQ(mean.height, 9);
  EXPECT_EQ(variance.width, 16);
  EXPECT_EQ(variance.height, 9);
  EXPECT_EQ(attribute(mean, "sssContent"), "mean");
  EXPECT_EQ(attribute(variance, "sssContent"), "variance");
  for (const sss::image::Image* im : {&mean, &variance}) {
    EXPECT_EQ(attribute(*im, "sssSpp"), "8");
    EXPECT_FALSE(attribute(*im, "sssTile").has_value()) << "a whole frame carries no tile";
    const auto settings = attribute(*im, "sssSettings");
    ASSERT_TRUE(settings.has_value());
    // The options that change the pixels, not the output names.
    EXPECT_NE(settings->find("builtin:sphere"), std::string::npos) << *settings;
    EXPECT_NE(settings->find("--spp 8"), std::string::npos) << *settings;
    EXPECT_EQ(settings->find(exr.string()), std::string::npos) << *settings;
    EXPECT_EQ(settings->find("--quiet"), std::string::npos) << *settings;
    ASSERT_TRUE(attribute(*im, "sssRelativeStandardError").has_value());
  }
  const double attr_error = std::stod(*attribute(mean, "sssRelativeStandardError"));
  EXPECT_TRUE(std::isfinite(attr_error) && attr_error > 0.0) << attr_error;
  // Some pixel sees the sphere, with a finite, non-negative variance.
  bool geometry = false;
  for (std::size_t i = 0; i < variance.rgba.size(); ++i) {
    EXPECT_TRUE(std::isfinite(variance.rgba[i]) && variance.rgba[i] >= 0.0f) << i;
    if (i % 4 == 3 && mean.rgba[i] > 0.5f) geometry = true;
  }
  EXPECT_TRUE(geometry);

  const nlohmann::json j = nlohmann::json::parse(slurp(json));
  for (const char* key : {"spp", "relative_standard_error", "paths", "scattering_events", "command"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j.value("spp", 0), 8);
  EXPECT_GT(j.value("paths", 0), 0);
  EXPECT_GT(j.value("scattering_events", 0), 0);
  EXPECT_NEAR(j.value("relative_standard_error", -1.0), attr_error, 1e-8 * attr_error);
  const std::string command = j.value("command", "");
  EXPECT_NE(command.find("--method random-walk"), std::string::npos) << command;
  EXPECT_NE(command.find("--spp 8"), std::string::npos) << command;
  EXPECT_EQ(entries(dir), 3u);
}

const std::string kSkinLayers = std::string(SSS_SOURCE_DIR) + "/assets/layers/skin-two-layers.json";

TEST(SssReferenceRandomWalk, BadInputExitsTwoNamingTheOptionAndWritesNothing) {
  const fs::path dir = folder("bad");
  const fs::path out = dir / "bad.exr", var = dir / "bad.var.exr";
  const std::string walk = "builtin:sphere --method random-walk --width 16 --height 9 --quiet --out " + out.string();
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {walk + " --spp 0", "--spp"},
      {walk + " --spp -3", "--spp"},
      {walk + " --target-error 0", "--target-error"},
      {walk + " --target-error 1.5", "--target-error"},
      {walk + " --target-error nan", "--target-error"},
      {walk + " --spp 4 --variance " + var.string() + " --tile 0/4", "--tile"},
      {walk + " --spp 4 --variance " + var.string() + " --tile 5/4", "--tile"},
      {walk + " --spp 4 --variance " + var.string() + " --tile 3", "--tile"},
      {walk + " --spp 4 --variance " + var.string() + " --tile a/b", "--tile"},
      {walk + " --spp 4 --tile 2/4", "--variance"},
      {walk + " --spp 4 --variance " + var.string() + " --tile 2/4 --target-error 0.1", "--tile"},
      {walk + " --spp 4 --variance " + var.string() + " --tile 20/20", "--tile"},  // 20 tiles, 9 rows
      {walk + " --spp 4 --spacing 1", "--spacing"},
      {"builtin:sphere --estimator octree --width 16 --height 9 --quiet --out " + out.string() + " --spp 4",
       "--spp"},  // the octree's error is set by its spacing
      {"builtin:sphere --method magic --width 16 --height 9 --quiet --out " + out.string(), "--method"},
      {walk + " --spp 4 --variance " + (dir / "x.png").string(), "--variance"},
      {walk + " --spp 4 --summary " + (dir / "x.txt").string(), "--summary"},
      // The same file as mean and variance: the message names the file.
      {walk + " --spp 4 --variance " + out.string(), out.string()},
      // Layered materials (issue 19): the walk does not follow a stack yet and says so; a
      // stack does not combine with another medium or model; a missing file is named.
      {walk + " --spp 4 --layers " + kSkinLayers, "layered"},
      {walk + " --spp 4 --layers " + kSkinLayers + " --model dipole", "--layers"},
      {walk + " --spp 4 --layers " + kSkinLayers + " --preset skin1", "--layers"},
      {walk + " --spp 4 --layers " + (dir / "none.json").string(), "none.json"},
  };
  for (const Case& c : cases) {
    const CliRun r = reference(c.args);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(entries(dir), 0u) << c.args << ": wrote something";
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(var));
}

// The diffusion reference's probe estimator (issue 17) writes the same three files, with
// the same attributes, and refuses what belongs to the other estimator or method.
TEST(SssReferenceProbe, WritesMeanVarianceAndSummaryAndRefusesOctreeOptions) {
  const fs::path dir = folder("probe");
  const fs::path exr = dir / "sphere.exr", var = dir / "sphere.var.exr", json = dir / "sphere.json";
  const CliRun r = reference("builtin:sphere --estimator probe --width 12 --height 8 --spp 4 --quiet --out " +
                             exr.string() + " --variance " + var.string() + " --summary " + json.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const sss::image::Image mean = read(exr), variance = read(var);
  EXPECT_EQ(attribute(mean, "sssContent"), "mean");
  EXPECT_EQ(attribute(variance, "sssContent"), "variance");
  EXPECT_EQ(attribute(mean, "sssSpp"), "4");
  bool lit = false;
  for (std::size_t i = 0; i < variance.rgba.size(); ++i) {
    EXPECT_TRUE(std::isfinite(variance.rgba[i]) && variance.rgba[i] >= 0.0f) << i;
    if (i % 4 != 3 && variance.rgba[i] > 0.0f) lit = true;
  }
  EXPECT_TRUE(lit) << "no pixel has a measured variance";
  const nlohmann::json j = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(j.value("estimator", ""), "probe");
  EXPECT_EQ(j.value("spp", 0), 4);
  EXPECT_GT(j.value("probes", 0), 0);
  EXPECT_GT(j.value("hits", 0), 0);
  EXPECT_EQ(entries(dir), 3u);

  const fs::path bad_dir = folder("probe-bad");
  const std::string out = (bad_dir / "x.exr").string();
  const std::string probe = "builtin:sphere --estimator probe --width 12 --height 8 --quiet --out " + out;
  const std::string octree = "builtin:sphere --estimator octree --width 12 --height 8 --quiet --out " + out;
  const std::string automatic = "builtin:sphere --width 12 --height 8 --quiet --out " + out;
  struct Case {
    std::string args, expect;
  };
  const Case cases[] = {
      {probe + " --spacing 1", "--spacing"},
      {probe + " --brute-force", "--brute-force"},
      {probe + " --tile 1/2", "--tile"},  // no fixed --spp, no --variance
      {octree + " --tile 1/2", "--tile"},  // the octree renders whole frames
      {probe + " --spp 0", "--spp"},
      {probe + " --target-error 2", "--target-error"},
      {octree + " --variance " + (bad_dir / "v.exr").string(), "--variance"},
      {automatic + " --estimator magic", "--estimator"},
      // auto with the options of both estimators: the octree's win, the probe's are named.
      {automatic + " --spacing 1 --spp 4", "--spp"},
      {automatic + " --brute-force --variance " + (bad_dir / "v.exr").string(), "--variance"},
      {"builtin:sphere --method random-walk --estimator probe --spp 2 --quiet --out " + out, "--estimator"},
      // The budget's switches (issue 17): named values, diffusion only, the size with the maps only.
      {octree + " --kernel gaussian", "--kernel"},
      {octree + " --shadows soft", "--shadows"},
      {octree + " --transmission sideways", "--transmission"},
      {probe + " --transmission local", "--transmission"},
      {"builtin:sphere --method random-walk --transmission off --spp 2 --quiet --out " + out, "--transmission"},
      {octree + " --thickness-from shadow-map", "--thickness-from"},  // without --transmission local
      {octree + " --transmission local --thickness-from sonar", "--thickness-from"},
      {probe + " --thickness-from shadow-map", "--thickness-from"},
      {octree + " --shadow-map-size 512", "--shadow-map-size"},
      {octree + " --transmission local --thickness-from shadow-map --shadow-map-size 0", "--shadow-map-size"},
      {octree + " --shadows shadow-map --shadow-map-size 0", "--shadow-map-size"},
      {"builtin:sphere --method random-walk --kernel fit --spp 2 --quiet --out " + out, "--kernel"},
      {"builtin:sphere --method random-walk --shadows shadow-map --spp 2 --quiet --out " + out, "--shadows"},
      // The scattered light alone: linear EXR, diffusion only, and not twice without specular.
      {"builtin:sphere --method random-walk --no-specular --spp 2 --quiet --out " + out, "--no-specular"},
      {octree + " --no-specular --diffuse-only", "--no-specular"},
      {"builtin:sphere --width 12 --height 8 --quiet --no-specular --out " + (bad_dir / "x.png").string(),
       "--no-specular"},
      {octree + " --no-specular --png " + (bad_dir / "x.png").string(), "--no-specular"},
  };
  for (const Case& c : cases) {
    const CliRun b = reference(c.args);
    EXPECT_EQ(b.code, 2) << c.args << "\n" << b.err;
    EXPECT_NE(b.err.find(c.expect), std::string::npos) << c.args << "\n" << b.err;
    EXPECT_EQ(entries(bad_dir), 0u) << c.args << ": wrote something";
  }
}

// The probe estimator's frame spread over machines as the ground truth's is (the README's
// GNU parallel and Slurm recipes): its batch k of pixel i draws from stream (seed, i, k),
// so two tiles merge into the very bytes of the whole frame, and a probe tile does not
// merge with a random-walk one (their settings differ).
TEST(SssReferenceProbe, TilesMergeBitIdenticallyToTheWholeFrame) {
  const fs::path dir = folder("probe-tiles");
  const std::string frame = "builtin:sphere --estimator probe --width 16 --height 9 --spp 3 --seed 5 --quiet";
  const CliRun w = reference(frame + " --out " + (dir / "whole.exr").string() + " --variance " +
                             (dir / "whole.var.exr").string());
  ASSERT_EQ(w.code, 0) << w.err;
  for (int k = 1; k <= 2; ++k) {
    const std::string t = "p" + std::to_string(k);
    const CliRun r = reference(frame + " --tile " + std::to_string(k) + "/2 --out " + (dir / (t + ".exr")).string() +
                               " --variance " + (dir / (t + ".var.exr")).string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const CliRun m = reference("merge" + files(dir, {"p2.exr", "p1.var.exr", "p1.exr", "p2.var.exr"}) + " --out " +
                             (dir / "merged.exr").string() + " --variance " + (dir / "merged.var.exr").string());
  ASSERT_EQ(m.code, 0) << m.err;
  const std::string whole = slurp(dir / "whole.exr");
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(slurp(dir / "merged.exr") == whole) << "merged.exr differs from whole.exr";
  EXPECT_TRUE(slurp(dir / "merged.var.exr") == slurp(dir / "whole.var.exr")) << "the variances differ";
  EXPECT_FALSE(slurp(dir / "p1.exr") == whole) << "a tile holds half the rows";
  EXPECT_EQ(attribute(read(dir / "p2.exr"), "sssTile"), "2/2");
  // Tile 2 of a random-walk render of the same frame does not complete the probe's tile 1.
  const CliRun r = reference("builtin:sphere --method random-walk --width 16 --height 9 --spp 3 --seed 5 --quiet "
                             "--tile 2/2 --out " + (dir / "w2.exr").string() + " --variance " +
                             (dir / "w2.var.exr").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path refused = dir / "refused.exr";
  const CliRun bad = reference("merge" + files(dir, {"p1.exr", "p1.var.exr", "w2.exr", "w2.var.exr"}) + " --out " +
                               refused.string());
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_NE(bad.err.find("other settings"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(refused));
}

TEST(SssReferenceRandomWalk, TilesMergeBitIdenticallyToTheWholeFrame) {
  const fs::path dir = folder("tiles");
  render_whole(dir);
  for (int k = 1; k <= 3; ++k) render_tile(dir, k);
  // Mean and variance tiles mixed, in no particular order.
  const CliRun m = reference("merge" + files(dir, {"t3.var.exr", "t2.exr", "t1.var.exr", "t3.exr", "t1.exr", "t2.var.exr"}) +
                             " --out " + (dir / "merged.exr").string() + " --variance " + (dir / "merged.var.exr").string());
  ASSERT_EQ(m.code, 0) << m.err;
  const std::string whole = slurp(dir / "whole.exr"), whole_var = slurp(dir / "whole.var.exr");
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(slurp(dir / "merged.exr") == whole) << "merged.exr differs from whole.exr";
  EXPECT_TRUE(slurp(dir / "merged.var.exr") == whole_var) << "merged.var.exr differs from whole.var.exr";
  // A tile is not the frame: it holds a third of the rows and says which.
  EXPECT_FALSE(slurp(dir / "t1.exr") == whole);
  EXPECT_EQ(attribute(read(dir / "t2.exr"), "sssTile"), "2/3");
  EXPECT_EQ(attribute(read(dir / "t2.var.exr"), "sssTile"), "2/3");
}

// Twelve tiles of 12 rows: the top and bottom rows see no sphere, so those tiles sample no
// pixel, yet they took the render's samples per pixel and merge with the others.
TEST(SssReferenceRandomWalk, TilesThatSeeNoMediumStillMerge) {
  const fs::path dir = folder("empty-tiles");
  render_whole(dir);
  std::string all;
  for (int k = 1; k <= 12; ++k) {
    const std::string t = "e" + std::to_string(k);
    const CliRun r = reference(kFrame + " --tile " + std::to_string(k) + "/12 --out " + (dir / (t + ".exr")).string() +
                               " --variance " + (dir / (t + ".var.exr")).string());
    ASSERT_EQ(r.code, 0) << r.err;
    all += " " + (dir / (t + ".exr")).string() + " " + (dir / (t + ".var.exr")).string();
  }
  EXPECT_EQ(attribute(read(dir / "e1.exr"), "sssSpp"), "16");
  const CliRun m = reference("merge" + all + " --out " + (dir / "merged.exr").string() + " --variance " +
                             (dir / "merged.var.exr").string());
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_TRUE(slurp(dir / "merged.exr") == slurp(dir / "whole.exr"));
  // merge refuses to write its frame and its variance into one file.
  const CliRun same = reference("merge" + all + " --out " + (dir / "x.exr").string() + " --variance " +
                                (dir / "x.exr").string());
  EXPECT_EQ(same.code, 2);
  EXPECT_NE(same.err.find("--variance"), std::string::npos) << same.err;
  EXPECT_NE(same.err.find("sss-reference merge --help"), std::string::npos) << same.err;
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

TEST(SssReferenceRandomWalk, ThreadCountDoesNotChangeTheImage) {
  const fs::path dir = folder("threads");
  std::string mean[2], var[2];
  for (int t = 1; t <= 2; ++t) {
    const fs::path out = dir / ("t" + std::to_string(t) + ".exr"), v = dir / ("t" + std::to_string(t) + ".var.exr");
    const CliRun r = reference(kFrame + " --threads " + std::to_string(t) + " --out " + out.string() + " --variance " +
                               v.string());
    ASSERT_EQ(r.code, 0) << r.err;
    mean[t - 1] = slurp(out);
    var[t - 1] = slurp(v);
  }
  ASSERT_FALSE(mean[0].empty());
  EXPECT_TRUE(mean[0] == mean[1]) << "--threads 1 and --threads 2 give different EXRs";
  EXPECT_TRUE(var[0] == var[1]) << "--threads 1 and --threads 2 give different variance EXRs";
}

TEST(SssReferenceRandomWalk, MergeRefusesTilesThatDoNotFitAndWritesNothing) {
  const fs::path dir = folder("merge-bad");
  render_whole(dir);
  for (int k = 1; k <= 3; ++k) render_tile(dir, k);
  {  // tile 2 again, with another seed
    const CliRun r = reference("builtin:sphere --method random-walk --width 24 --height 12 --spp 16 --seed 4 --quiet "
                               "--tile 2/3 --out " + (dir / "seed4.exr").string() + " --variance " +
                               (dir / "seed4.var.exr").string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  {  // an EXR of the diffusion reference
    const CliRun r = reference("builtin:sphere --width 24 --height 12 --spacing 3 --quiet --out " +
                               (dir / "diffusion.exr").string());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const std::size_t before = entries(dir);
  const fs::path out = dir / "m.exr", var = dir / "m.var.exr";
  struct Case {
    std::vector<std::string> files;
    std::string expect;
  };
  const Case cases[] = {
      {{"t1.exr", "t2.exr", "t3.exr", "t1.var.exr", "t2.var.exr"}, "missing"},
      {{"t1.exr", "t2.exr", "t3.exr", "t1.exr", "t1.var.exr", "t2.var.exr", "t3.var.exr"}, "again"},
      {{"t1.exr", "seed4.exr", "t3.exr", "t1.var.exr", "seed4.var.exr", "t3.var.exr"}, "other settings"},
      {{"t1.exr", "whole.exr", "t3.exr", "t1.var.exr", "t2.var.exr", "t3.var.exr"}, "not a tile"},
      {{"t1.exr", "diffusion.exr", "t3.exr", "t1.var.exr", "t2.var.exr", "t3.var.exr"}, "diffusion.exr"},
      {{"t1.exr", "nope.exr", "t3.exr", "t1.var.exr", "t2.var.exr", "t3.var.exr"}, "nope.exr"},
  };
  for (const Case& c : cases) {
    const std::string args = "merge" + files(dir, c.files) + " --out " + out.string() + " --variance " + var.string();
    const CliRun r = reference(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
    EXPECT_FALSE(fs::exists(var)) << args;
    EXPECT_EQ(entries(dir), before) << args << ": wrote something";
  }
  // The diffusion EXR is refused for what it is, not for failing to open.
  const CliRun d = reference("merge" + files(dir, {"t1.exr", "diffusion.exr", "t3.exr", "t1.var.exr", "t2.var.exr",
                                                   "t3.var.exr"}) + " --out " + out.string());
  EXPECT_NE(d.err.find("not a tile of a per-pixel Monte Carlo render"), std::string::npos) << d.err;
}

TEST(SssReferenceRandomWalk, GnuParallelSpreadsTilesThatMergeBitIdentically) {
  // The README's scale-out recipe, for real: GNU parallel runs the three tile renders
  // (scripts/install-deps.sh installs it; a machine without it fails here rather than
  // skipping the check).
  ASSERT_EQ(sss::testing::run_shell("command -v parallel").code, 0)
      << "GNU parallel is not installed: run scripts/install-deps.sh (Debian package 'parallel')";
  const fs::path dir = folder("parallel");
  render_whole(dir);
  const std::string exe = SSS_REFERENCE_EXE;
  const std::string cmd = "parallel --will-cite --halt now,fail=1 " + exe + " " + kFrame + " --threads 1 --tile {}/3 --out " +
                          (dir / "t{}.exr").string() + " --variance " + (dir / "t{}.var.exr").string() + " ::: 1 2 3";
  const CliRun p = sss::testing::run_shell(cmd);
  ASSERT_EQ(p.code, 0) << cmd << "\n" << p.out;
  const CliRun m = reference("merge" + files(dir, {"t1.exr", "t2.exr", "t3.exr", "t1.var.exr", "t2.var.exr", "t3.var.exr"}) +
                             " --out " + (dir / "merged.exr").string() + " --variance " + (dir / "merged.var.exr").string());
  ASSERT_EQ(m.code, 0) << m.err;
  const std::string whole = slurp(dir / "whole.exr");
  ASSERT_FALSE(whole.empty());
  EXPECT_TRUE(slurp(dir / "merged.exr") == whole) << "merged.exr differs from whole.exr";
  EXPECT_TRUE(slurp(dir / "merged.var.exr") == slurp(dir / "whole.var.exr")) << "the variance files differ";
}

// Starts a random-walk render far too long to finish (builtin:bunny, 640x360, 100000
// samples per pixel, one thread) into `out` and `variance`, sends `sig` 1.5 s later and
// returns the wait status (-1 if the process could not be started or waited for).
int walk_and_signal(const fs::path& out, const fs::path& variance, int sig) {
  const std::string exe = SSS_REFERENCE_EXE;
  std::vector<std::string> args = {exe,     "builtin:bunny", "--method",   "random-walk",     "--spp",
                                   "100000", "--threads",    "1",          "--quiet",         "--out",
                                   out.string(), "--variance", variance.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawn(&pid, exe.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, sig);
  int status = 0;
  return ::waitpid(pid, &status, 0) == pid ? status : -1;
}

TEST(SssReferenceRandomWalk, CtrlCStopsWithoutWritingMeanOrVariance) {
  const fs::path dir = folder("interrupted");
  const fs::path out = dir / "walk.exr", var = dir / "walk.var.exr";
  const int status = walk_and_signal(out, var, SIGINT);
  ASSERT_NE(status, -1) << "could not start or wait for " << SSS_REFERENCE_EXE;
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal instead of stopping cleanly";
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(var));
  EXPECT_EQ(entries(dir), 0u) << "a temporary or partial file was left";
}

}  // namespace

#endif  // SSS_REFERENCE_EXE
