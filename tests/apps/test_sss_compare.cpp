// Every documented sss-compare command and every documented error (DESIGN.md §4, README
// "sss-compare"): exit 0 when the images agree, 3 when they do not, 2 for bad usage or
// input with the file or option named on stderr, 1 for a runtime failure (the heat map
// cannot be written, and then no file is left); --json prints exactly one JSON document.
//
// The inputs are written here by a minimal PNG encoder (stored deflate blocks) and a
// minimal uncompressed OpenEXR encoder, independent of the code under test.
#ifdef SSS_COMPARE_EXE

#include "common/CliRun.h"
#include "image/Image.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct Pixels {
  int w = 0, h = 0;
  std::vector<float> rgba;  // row-major, 4 per pixel
  float* at(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * w + x) * 4]; }
};

Pixels make(int w, int h, const std::function<std::array<float, 4>(int, int)>& f) {
  Pixels p{w, h, std::vector<float>(static_cast<std::size_t>(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto v = f(x, y);
      std::copy(v.begin(), v.end(), p.at(x, y));
    }
  return p;
}

// A textured image in [0.2, 0.7] with alpha 1.
Pixels texture(int w, int h) {
  return make(w, h, [](int x, int y) -> std::array<float, 4> {
    const float v = 0.45f + 0.25f * std::sin(0.7f * x) * std::cos(0.45f * y);
    return {v, 0.9f * v, 0.8f * v + 0.05f, 1.0f};
  });
}

Pixels scaled(Pixels p, float k) {
  for (std::size_t i = 0; i < p.rgba.size(); ++i)
    if (i % 4 != 3) p.rgba[i] *= k;
  return p;
}

void put32be(std::string& s, std::uint32_t v) {
  for (int i = 3; i >= 0; --i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}

std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void chunk(std::string& png, const char* type, const std::string& data) {
  put32be(png, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  put32be(png, crc32(body));
}

// 8-bit PNG, RGBA or (with_alpha false) RGB; values clamped to [0, 1] and rounded.
void write_png(const fs::path& path, const Pixels& p, bool with_alpha = true) {
  const int channels = with_alpha ? 4 : 3;
  std::string raw;
  for (int y = 0; y < p.h; ++y) {
    raw += '\0';  // filter: none
    for (int x = 0; x < p.w; ++x)
      for (int c = 0; c < channels; ++c) {
        const float v = std::clamp(p.rgba[(static_cast<std::size_t>(y) * p.w + x) * 4 + c], 0.0f, 1.0f);
        raw += static_cast<char>(static_cast<unsigned char>(std::lround(v * 255.0f)));
      }
  }
  std::string z = "\x78\x01";  // zlib header, then stored deflate blocks
  for (std::size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - off);
    z += static_cast<char>(off + n >= raw.size() ? 1 : 0);
    for (std::uint32_t v : {static_cast<std::uint32_t>(n), static_cast<std::uint32_t>(~n & 0xffff)}) {
      z += static_cast<char>(v & 0xff);
      z += static_cast<char>((v >> 8) & 0xff);
    }
    z += raw.substr(off, n);
    if (n == 0) break;
  }
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  put32be(z, (b << 16) | a);
  std::string png = "\x89PNG\r\n\x1a\n";
  std::string ihdr;
  put32be(ihdr, static_cast<std::uint32_t>(p.w));
  put32be(ihdr, static_cast<std::uint32_t>(p.h));
  ihdr += std::string{'\x08', with_alpha ? '\x06' : '\x02', '\0', '\0', '\0'};
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  std::ofstream(path, std::ios::binary) << png;
}

template <class T>
void put_le(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // the test machines are little-endian, as EXR is
  s.append(b, sizeof(T));
}

void attribute(std::string& s, const char* name, const char* type, const std::string& value) {
  s += name;
  s += '\0';
  s += type;
  s += '\0';
  put_le<std::int32_t>(s, static_cast<std::int32_t>(value.size()));
  s += value;
}

// Uncompressed scanline OpenEXR with 32-bit float channels A (if with_alpha), B, G, R.
void write_exr(const fs::path& path, const Pixels& p, bool with_alpha = true) {
  const std::vector<std::pair<char, int>> channels =
      with_alpha ? std::vector<std::pair<char, int>>{{'A', 3}, {'B', 2}, {'G', 1}, {'R', 0}}
                 : std::vector<std::pair<char, int>>{{'B', 2}, {'G', 1}, {'R', 0}};
  std::string chlist;
  for (const auto& ch : channels) {
    chlist += ch.first;
    chlist += '\0';
    put_le<std::int32_t>(chlist, 2);  // FLOAT
    chlist += std::string(4, '\0');   // pLinear, reserved
    put_le<std::int32_t>(chlist, 1);
    put_le<std::int32_t>(chlist, 1);
  }
  chlist += '\0';
  std::string box;
  for (std::int32_t v : {0, 0, p.w - 1, p.h - 1}) put_le(box, v);
  std::string one, center;
  put_le(one, 1.0f);
  put_le(center, 0.0f);
  put_le(center, 0.0f);
  std::string exr = std::string("\x76\x2f\x31\x01", 4) + std::string("\x02\0\0\0", 4);
  attribute(exr, "channels", "chlist", chlist);
  attribute(exr, "compression", "compression", std::string(1, '\0'));
  attribute(exr, "dataWindow", "box2i", box);
  attribute(exr, "displayWindow", "box2i", box);
  attribute(exr, "lineOrder", "lineOrder", std::string(1, '\0'));
  attribute(exr, "pixelAspectRatio", "float", one);
  attribute(exr, "screenWindowCenter", "v2f", center);
  attribute(exr, "screenWindowWidth", "float", one);
  exr += '\0';
  const std::size_t line = static_cast<std::size_t>(p.w) * channels.size() * 4;
  const std::size_t table_end = exr.size() + 8 * static_cast<std::size_t>(p.h);
  for (int y = 0; y < p.h; ++y) put_le<std::uint64_t>(exr, table_end + y * (8 + line));
  for (int y = 0; y < p.h; ++y) {
    put_le<std::int32_t>(exr, y);
    put_le<std::int32_t>(exr, static_cast<std::int32_t>(line));
    for (const auto& ch : channels)
      for (int x = 0; x < p.w; ++x)
        put_le(exr, p.rgba[(static_cast<std::size_t>(y) * p.w + x) * 4 + ch.second]);
  }
  std::ofstream(path, std::ios::binary) << exr;
}

using sss::testing::CliRun;
using sss::testing::slurp;

// A fresh folder per test, removed when the test ends.
class SssCompare : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("sss-compare-test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  CliRun run(const std::string& args) const {
    return sss::testing::run_cli(SSS_COMPARE_EXE, args, dir_ / "stderr.txt");
  }

  // Only temporaries and what the test wrote itself may be in the folder.
  bool no_temporaries() const {
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().filename().string().find(".tmp") != std::string::npos) return false;
    return true;
  }

  fs::path dir_;
};

bool contains(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

// Width and height from a PNG's IHDR.
std::pair<int, int> png_size(const std::string& bytes) {
  auto be = [&](std::size_t off) {
    return (static_cast<unsigned char>(bytes[off]) << 24) | (static_cast<unsigned char>(bytes[off + 1]) << 16) |
           (static_cast<unsigned char>(bytes[off + 2]) << 8) | static_cast<unsigned char>(bytes[off + 3]);
  };
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return {0, 0};
  return {be(16), be(20)};
}

}  // namespace

TEST_F(SssCompare, HelpDocumentsOptionsAndExitCodes) {
  const CliRun r = run("--help");
  EXPECT_EQ(r.code, 0);
  for (const char* s : {"--heatmap", "--heatmap-max", "--heatmap-signed", "--exclude-silhouettes", "--log-ratio", "--log-range", "--json", "--tolerance", "--max-abs",
                        "--max-fraction", "--min-ssim", "--threshold", "--exposure", "3 they do not"})
    EXPECT_TRUE(contains(r.out, s)) << s;
}

TEST_F(SssCompare, IdenticalPngsPass) {
  write_png(path("a.png"), texture(24, 16));
  const CliRun r = run(path("a.png") + " " + path("a.png"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  for (const char* s : {"relative RMSE", "RMSE", "PSNR", "max abs error", "over threshold", "SSIM",
                        "compared 384 of 384 pixels", "result: PASS", "inf"})
    EXPECT_TRUE(contains(r.out, s)) << s << "\n" << r.out;
}

TEST_F(SssCompare, JsonIsOneDocumentWithTheContract) {
  write_png(path("a.png"), texture(24, 16));
  const CliRun r = run(path("a.png") + " " + path("a.png") + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);  // throws unless exactly one document
  EXPECT_EQ(doc["pass"], true);
  EXPECT_EQ(doc["space"], "display");
  EXPECT_EQ(doc["a"]["width"], 24);
  EXPECT_EQ(doc["a"]["encoding"], "display");
  EXPECT_EQ(doc["pixels"]["compared"], 384);
  EXPECT_EQ(doc["pixels"]["total"], 384);
  EXPECT_EQ(doc["pixels"]["excluded"], 0);
  EXPECT_DOUBLE_EQ(doc["threshold"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(doc["tolerance"].get<double>(), 0.01);
  const auto& m = doc["metrics"];
  EXPECT_EQ(m["rmse"].get<double>(), 0.0);
  EXPECT_EQ(m["relative_rmse"].get<double>(), 0.0);
  EXPECT_TRUE(m["psnr_db"].is_null());  // +∞
  EXPECT_EQ(m["max_abs_error"].get<double>(), 0.0);
  EXPECT_EQ(m["fraction_over_threshold"].get<double>(), 0.0);
  EXPECT_EQ(m["ssim"].get<double>(), 1.0);
  EXPECT_EQ(m["peak"].get<double>(), 1.0);
  ASSERT_EQ(doc["limits"].size(), 1u);
  EXPECT_EQ(doc["limits"][0]["metric"], "relative_rmse");
  EXPECT_TRUE(doc["heatmap"].is_null());
}

TEST_F(SssCompare, DifferentImagesExitThreeAndTheToleranceDecides) {
  write_png(path("b.png"), texture(24, 16));
  write_png(path("a.png"), scaled(texture(24, 16), 1.1f));
  const std::string ab = path("a.png") + " " + path("b.png");
  const CliRun r = run(ab + " --json");
  EXPECT_EQ(r.code, 3) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["pass"], false);
  EXPECT_EQ(doc["limits"][0]["pass"], false);
  const double rel = doc["metrics"]["relative_rmse"].get<double>();
  EXPECT_NEAR(rel, 0.1, 0.01);  // A = 1.1 B, within 8-bit rounding
  const CliRun text = run(ab);
  EXPECT_EQ(text.code, 3);
  EXPECT_TRUE(contains(text.out, "result: FAIL (relative RMSE")) << text.out;
  EXPECT_EQ(run(ab + " --tolerance 0.15").code, 0);
  EXPECT_EQ(run(ab + " --tolerance 0.05").code, 3);
}

TEST_F(SssCompare, ExtraLimitsEachFailOnTheirOwn) {
  write_png(path("b.png"), texture(24, 16));
  Pixels a = texture(24, 16);
  for (int x = 0; x < 4; ++x) a.at(x, 3)[0] += 0.2f;  // 4 pixels with error 0.2 (~1%)
  write_png(path("a.png"), a);
  const std::string ab = path("a.png") + " " + path("b.png") + " --tolerance 0.5 --json ";
  const auto base = nlohmann::json::parse(run(ab).out);
  EXPECT_EQ(base["pass"], true);
  EXPECT_NEAR(base["metrics"]["max_abs_error"].get<double>(), 0.2, 1.0 / 255);
  EXPECT_EQ(base["metrics"]["pixels_over_threshold"], 4);
  EXPECT_LT(base["metrics"]["max_abs_error_at"][0].get<int>(), 4);
  EXPECT_EQ(base["metrics"]["max_abs_error_at"][1], 3);
  struct Case {
    std::string flags, metric;
    int code;
  };
  for (const Case& c : {Case{"--max-abs 0.1", "max_abs_error", 3}, Case{"--max-abs 0.3", "max_abs_error", 0},
                        Case{"--max-fraction 0.005", "fraction_over_threshold", 3},
                        Case{"--max-fraction 0.05", "fraction_over_threshold", 0},
                        Case{"--min-ssim 0.9999", "ssim", 3}, Case{"--min-ssim 0.5", "ssim", 0},
                        Case{"--threshold 0.5 --max-fraction 0", "fraction_over_threshold", 0}}) {
    const CliRun r = run(ab + c.flags);
    EXPECT_EQ(r.code, c.code) << c.flags << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    ASSERT_EQ(doc["limits"].size(), 2u) << c.flags;
    EXPECT_EQ(doc["limits"][1]["metric"], c.metric);
    EXPECT_EQ(doc["limits"][1]["pass"], c.code == 0) << c.flags;
  }
}

TEST_F(SssCompare, ExrPairIsComparedLinearlyAgainstTheReferencePeak) {
  Pixels b = texture(20, 12);
  b.at(2, 2)[1] = 8.0f;  // HDR: the reference's peak
  write_exr(path("b.exr"), b);
  write_exr(path("a.exr"), scaled(b, 1.25f));
  const CliRun r = run(path("a.exr") + " " + path("b.exr") + " --json --tolerance 0.3");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["space"], "linear");
  EXPECT_EQ(doc["b"]["encoding"], "linear");
  EXPECT_DOUBLE_EQ(doc["metrics"]["peak"].get<double>(), 8.0);
  EXPECT_NEAR(doc["metrics"]["relative_rmse"].get<double>(), 0.25, 1e-6);  // float data: exact
  EXPECT_NEAR(doc["metrics"]["max_abs_error"].get<double>(), 2.0, 1e-6);
  EXPECT_LT(doc["metrics"]["ssim"].get<double>(), 1.0);
}

TEST_F(SssCompare, PngAgainstExrTonemapsTheExr) {
  const Pixels hdr = texture(16, 16);
  write_exr(path("ref.exr"), hdr);
  write_png(path("a.png"), hdr);
  const CliRun r = run(path("a.png") + " " + path("ref.exr") + " --json --tolerance 1");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["space"], "display");
  EXPECT_EQ(doc["a"]["tonemapped"], false);
  EXPECT_EQ(doc["b"]["tonemapped"], true);
  EXPECT_EQ(doc["b"]["encoding"], "linear");
  EXPECT_GT(doc["metrics"]["rmse"].get<double>(), 0.0);  // the filmic curve changed B
  const CliRun text = run(path("a.png") + " " + path("ref.exr") + " --tolerance 1 --exposure 2");
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_TRUE(contains(text.out, "tonemapped at exposure 2")) << text.out;
}

TEST_F(SssCompare, BackgroundIsExcludedAndCounted) {
  const Pixels ref = texture(20, 10);
  Pixels a = ref, b = ref;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 5; ++x) {
      a.at(x, y)[3] = 0.0f;  // A: no geometry in columns 0..4, and garbage there
      a.at(x, y)[0] = 1.0f - a.at(x, y)[0];
    }
  for (int x = 0; x < 20; ++x) b.at(x, 9)[3] = 0.0f;  // B: none in the last row
  for (auto [ext, writer] : {std::pair{".png", &write_png}, {".exr", &write_exr}}) {
    writer(path(std::string("a") + ext), a, true);
    writer(path(std::string("b") + ext), b, true);
    const CliRun r = run(path(std::string("a") + ext) + " " + path(std::string("b") + ext) + " --json");
    ASSERT_EQ(r.code, 0) << ext << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["pixels"]["compared"], 15 * 9) << ext;
    EXPECT_EQ(doc["pixels"]["excluded"], 200 - 15 * 9) << ext;
    EXPECT_EQ(doc["metrics"]["rmse"].get<double>(), 0.0) << ext;
    EXPECT_EQ(doc["metrics"]["ssim"].get<double>(), 1.0) << ext;
  }
}

TEST_F(SssCompare, ImagesWithoutAlphaAreAllGeometry) {
  write_png(path("a.png"), texture(8, 8), false);
  write_exr(path("b.exr"), texture(8, 8), false);
  for (const std::string& f : {path("a.png"), path("b.exr")}) {
    const CliRun r = run(f + " " + f + " --json");
    ASSERT_EQ(r.code, 0) << f << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["pixels"]["compared"], 64) << f;
  }
}

TEST_F(SssCompare, HeatMapIsWrittenWithItsColourBar) {
  write_png(path("b.png"), texture(40, 30));
  write_png(path("a.png"), scaled(texture(40, 30), 1.2f));
  const std::string heat = path("heat.png");
  const CliRun r = run(path("a.png") + " " + path("b.png") + " --heatmap " + heat + " --json");
  EXPECT_EQ(r.code, 3) << r.err;  // the heat map is written whether or not they agree
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["heatmap"]["path"], heat);
  // The default scale is the 99th percentile of the errors: at most 1% of the 1200 pixels
  // above it (ties at the percentile are not above).
  EXPECT_EQ(doc["heatmap"]["scale"], "p99");
  EXPECT_LE(doc["heatmap"]["max"].get<double>(), doc["metrics"]["max_abs_error"].get<double>());
  EXPECT_LE(doc["heatmap"]["pixels_above"].get<int>(), 12);
  EXPECT_EQ(doc["heatmap"]["signed"], false);
  const auto [w, h] = png_size(slurp(heat));
  EXPECT_GT(w, 40 + 20);  // the image, then the bar and its labels to its right
  EXPECT_GE(h, 30);
  EXPECT_TRUE(no_temporaries());
  const CliRun fixed = run(path("a.png") + " " + path("b.png") + " --heatmap " + heat + " --heatmap-max 0.5");
  EXPECT_EQ(fixed.code, 3);
  EXPECT_TRUE(contains(fixed.out, "heat map: " + heat + " (error 0 to 0.5)")) << fixed.out;
}

// The case: one bright spike (a silhouette's specular pixel) set the scale, and
// the rest of the map was the bottom colour. Values exact in binary: B 0.5 everywhere, A
// 0.625 (error 0.125) but one pixel 1.5 (error 1). The 99th percentile is 0.125, the
// spike is the one pixel above it, and the map's pixels are mid-map, not black.
TEST_F(SssCompare, HeatMapScaleIsTheNinetyNinthPercentileNotASpike) {
  const auto flat = [](float v) {
    return make(20, 10, [v](int, int) -> std::array<float, 4> { return {v, v, v, 1.0f}; });
  };
  Pixels a = flat(0.625f);
  for (int c = 0; c < 3; ++c) a.at(3, 4)[c] = 1.5f;
  write_exr(path("a.exr"), a);
  write_exr(path("b.exr"), flat(0.5f));
  const std::string heat = path("heat.png");
  const CliRun r = run(path("a.exr") + " " + path("b.exr") + " --heatmap " + heat + " --json");
  EXPECT_EQ(r.code, 3) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["metrics"]["max_abs_error"].get<double>(), 1.0);
  EXPECT_EQ(doc["heatmap"]["max"].get<double>(), 0.125);
  EXPECT_EQ(doc["heatmap"]["pixels_above"].get<int>(), 1);
  auto map = sss::image::read_image(heat);
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(map));
  const sss::image::Image& m = std::get<sss::image::Image>(map);
  // Every pixel at the top of the scale: viridis(1), yellow (R and G high, B low).
  const float* p = m.pixel(10, 5);
  EXPECT_GT(p[0], 0.8f);
  EXPECT_GT(p[1], 0.8f);
  EXPECT_LT(p[2], 0.3f);
  const CliRun table = run(path("a.exr") + " " + path("b.exr") + " --heatmap " + heat);
  EXPECT_TRUE(contains(table.out, "(error 0 to 0.125, the 99th percentile)")) << table.out;
  EXPECT_TRUE(contains(table.out, "1 pixels above the scale")) << table.out;
}

// --heatmap-signed: A above B on the left half, below on the right, by 0.125 both ways;
// the map is red on the left and blue on the right, its scale -0.125..+0.125.
TEST_F(SssCompare, SignedHeatMapIsRedWhereAIsAboveAndBlueBelow) {
  const Pixels b = make(20, 10, [](int, int) -> std::array<float, 4> { return {0.5f, 0.5f, 0.5f, 1.0f}; });
  const Pixels a = make(20, 10, [](int x, int) -> std::array<float, 4> {
    const float v = x < 10 ? 0.625f : 0.375f;
    return {v, v, v, 1.0f};
  });
  write_exr(path("a.exr"), a);
  write_exr(path("b.exr"), b);
  const std::string heat = path("signed.png");
  const CliRun r = run(path("a.exr") + " " + path("b.exr") + " --heatmap " + heat + " --heatmap-signed --json");
  EXPECT_EQ(r.code, 3) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["heatmap"]["signed"], true);
  EXPECT_EQ(doc["heatmap"]["max"].get<double>(), 0.125);
  auto map = sss::image::read_image(heat);
  ASSERT_TRUE(std::holds_alternative<sss::image::Image>(map));
  const sss::image::Image& m = std::get<sss::image::Image>(map);
  const float* left = m.pixel(2, 5);
  const float* right = m.pixel(17, 5);
  EXPECT_GT(left[0], 2.0f * left[2]) << "red where A is above";
  EXPECT_GT(right[2], 2.0f * right[0]) << "blue where A is below";
  const CliRun table = run(path("a.exr") + " " + path("b.exr") + " --heatmap " + heat + " --heatmap-signed");
  EXPECT_TRUE(contains(table.out, "signed error a-b, -0.125 to +0.125")) << table.out;
  const CliRun alone = run(path("a.exr") + " " + path("b.exr") + " --heatmap-signed");
  EXPECT_EQ(alone.code, 2) << "--heatmap-signed needs --heatmap";
}

// --exclude-silhouettes leaves out the ring of geometry next to background, as the golden
// suite does: a 10x10 square of geometry in a 20x20 frame whose only errors are on its
// outermost ring (36 pixels) compares equal with it, and not without it. Geometry that
// reaches the frame's border has no silhouette there.
TEST_F(SssCompare, ExcludeSilhouettesLeavesOutTheRingNextToBackground) {
  const auto square = [](float ring) {
    return make(20, 20, [ring](int x, int y) -> std::array<float, 4> {
      const bool inside = x >= 5 && x < 15 && y >= 5 && y < 15;
      const bool edge = inside && (x == 5 || x == 14 || y == 5 || y == 14);
      const float v = edge ? ring : 0.5f;
      return {v, v, v, inside ? 1.0f : 0.0f};
    });
  };
  write_exr(path("a.exr"), square(0.75f));
  write_exr(path("b.exr"), square(0.5f));
  const CliRun all = run(path("a.exr") + " " + path("b.exr") + " --json");
  EXPECT_EQ(all.code, 3) << all.err;
  EXPECT_GT(nlohmann::json::parse(all.out)["metrics"]["relative_rmse"].get<double>(), 0.1);
  EXPECT_TRUE(nlohmann::json::parse(all.out)["pixels"]["silhouette"].is_null());
  const CliRun inner = run(path("a.exr") + " " + path("b.exr") + " --exclude-silhouettes --json");
  EXPECT_EQ(inner.code, 0) << inner.out << inner.err;
  const auto doc = nlohmann::json::parse(inner.out);
  EXPECT_EQ(doc["pixels"]["silhouette"].get<int>(), 36);
  EXPECT_EQ(doc["pixels"]["compared"].get<int>(), 64);
  EXPECT_EQ(doc["metrics"]["relative_rmse"].get<double>(), 0.0);
  const CliRun table = run(path("a.exr") + " " + path("b.exr") + " --exclude-silhouettes");
  EXPECT_TRUE(contains(table.out, "(300 without geometry in A or B, 36 at a silhouette)")) << table.out;
  // All geometry: the frame's border is not a silhouette.
  const Pixels full = texture(12, 8);
  write_exr(path("full.exr"), full);
  const CliRun whole = run(path("full.exr") + " " + path("full.exr") + " --exclude-silhouettes --json");
  EXPECT_EQ(nlohmann::json::parse(whole.out)["pixels"]["silhouette"].get<int>(), 0);
  // Only a silhouette in common: nothing to compare, said with the count.
  const auto thin = make(20, 20, [](int x, int y) -> std::array<float, 4> {
    return {0.5f, 0.5f, 0.5f, x == 4 && y >= 5 && y < 15 ? 1.0f : 0.0f};
  });
  write_exr(path("thin.exr"), thin);
  const CliRun none = run(path("thin.exr") + " " + path("thin.exr") + " --exclude-silhouettes");
  EXPECT_EQ(none.code, 2);
  EXPECT_TRUE(contains(none.err, "--exclude-silhouettes left out 10")) << none.err;
}

TEST_F(SssCompare, HeatMapThatCannotBeWrittenIsARuntimeFailure) {
  write_png(path("a.png"), texture(8, 8));
  const std::string heat = path("no-such-folder/heat.png");
  const CliRun r = run(path("a.png") + " " + path("a.png") + " --heatmap " + heat + " --json");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_TRUE(contains(r.err, heat)) << r.err;
  EXPECT_FALSE(fs::exists(heat));
  EXPECT_TRUE(no_temporaries());
}

// --log-ratio: A is B twice as bright on its left half, so log2(A/B) of the luminance is
// exactly +1 there (doubling is exact in float) and 0 on the right: mean 0.5, half the
// pixels more than 5% brighter, none darker. The map is the image and its colour bar.
TEST_F(SssCompare, LogRatioMapIsWrittenWithItsStatistics) {
  const Pixels b = texture(40, 30);
  Pixels a = b;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 20; ++x)
      for (int c = 0; c < 3; ++c) a.at(x, y)[c] *= 2.0f;
  write_exr(path("a.exr"), a);
  write_exr(path("b.exr"), b);
  const std::string lr = path("ratio.png");
  const CliRun r = run(path("a.exr") + " " + path("b.exr") + " --log-ratio " + lr + " --json");
  EXPECT_EQ(r.code, 3) << r.err;  // written whether or not they agree
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["log_ratio"]["path"], lr);
  EXPECT_EQ(doc["log_ratio"]["range_stops"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(doc["log_ratio"]["mean_log2"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(doc["log_ratio"]["mean_abs_log2"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(doc["log_ratio"]["fraction_brighter"].get<double>(), 0.5);
  EXPECT_EQ(doc["log_ratio"]["fraction_darker"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(doc["log_ratio"]["tolerance"].get<double>(), 0.05);
  EXPECT_TRUE(doc["heatmap"].is_null());
  const auto [w, h] = png_size(slurp(lr));
  EXPECT_GT(w, 40 + 20);  // the image, then the bar and its signed labels to its right
  EXPECT_GE(h, 30);
  EXPECT_TRUE(no_temporaries());
  // Swapped, the sign flips; a wider range is stated in the table.
  const CliRun swapped = run(path("b.exr") + " " + path("a.exr") + " --log-ratio " + lr +
                             " --log-range 2 --heatmap " + path("heat.png"));
  EXPECT_EQ(swapped.code, 3) << swapped.err;
  EXPECT_TRUE(contains(swapped.out, "log ratio map: " + lr + " (log2(A/B) of the luminance, -2 to +2 stops)"))
      << swapped.out;
  EXPECT_TRUE(contains(swapped.out, "mean log2(A/B) -0.5")) << swapped.out;
  EXPECT_TRUE(fs::exists(path("heat.png")));
  // PNGs: the codes are sRGB-decoded, so a pair of PNGs gives a ratio of light. The
  // same light (scaled into [0, 1]) encoded by the sRGB formula (IEC 61966-2-1): 0.5 stop
  // on average again, to the codes' rounding.
  const auto encode = [](Pixels p) {
    for (std::size_t i = 0; i < p.rgba.size(); ++i)
      if (i % 4 != 3) {
        const float v = 0.4f * p.rgba[i];
        p.rgba[i] = sss::image::srgb_encode(v);
      }
    return p;
  };
  write_png(path("a.png"), encode(a));
  write_png(path("b.png"), encode(b));
  const CliRun png = run(path("a.png") + " " + path("b.png") + " --log-ratio " + lr + " --json");
  EXPECT_EQ(png.code, 3) << png.err;
  EXPECT_NEAR(nlohmann::json::parse(png.out)["log_ratio"]["mean_log2"].get<double>(), 0.5, 0.02);
}

TEST_F(SssCompare, BadLogRangeIsRefusedAndNothingIsWritten) {
  write_png(path("a.png"), texture(8, 8));
  const std::string aa = path("a.png") + " " + path("a.png") + " --json ";
  const std::string lr = path("lr.png");
  for (const char* range : {"0", "-1", "nan", "inf", "-inf", "abc", "1e999"}) {
    const CliRun r = run(aa + "--log-ratio " + lr + " --log-range " + std::string(range));
    EXPECT_EQ(r.code, 2) << range;
    EXPECT_TRUE(r.out.empty()) << range << r.out;
    EXPECT_TRUE(contains(r.err, "--log-range")) << range << "\n" << r.err;
    EXPECT_FALSE(fs::exists(lr)) << range;
  }
  const CliRun alone = run(aa + "--log-range 1");  // without a map to draw
  EXPECT_EQ(alone.code, 2);
  EXPECT_TRUE(contains(alone.err, "--log-ratio")) << alone.err;
  const CliRun jpg = run(aa + "--log-ratio " + path("lr.jpg"));
  EXPECT_EQ(jpg.code, 2);
  EXPECT_TRUE(contains(jpg.err, "--log-ratio")) << jpg.err;
  EXPECT_FALSE(fs::exists(path("lr.jpg")));
  // A folder that does not exist: a runtime failure, the file named, nothing left.
  const std::string nowhere = path("no-such-folder/lr.png");
  const CliRun unwritable = run(aa + "--log-ratio " + nowhere);
  EXPECT_EQ(unwritable.code, 1);
  EXPECT_TRUE(contains(unwritable.err, nowhere)) << unwritable.err;
  EXPECT_FALSE(fs::exists(nowhere));
  EXPECT_TRUE(no_temporaries());
  EXPECT_EQ(run(aa + "--log-ratio " + lr + " --log-range 0.25").code, 0);
  EXPECT_TRUE(fs::exists(lr));
}

TEST_F(SssCompare, SizeMismatchNamesBothFilesAndSizes) {
  write_png(path("a.png"), texture(8, 8));
  write_exr(path("b.exr"), texture(9, 7));
  const CliRun r = run(path("a.png") + " " + path("b.exr") + " --heatmap " + path("heat.png"));
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(r.out.empty());
  for (const std::string& s : {path("a.png") + " is 8x8", path("b.exr") + " is 9x7"})
    EXPECT_TRUE(contains(r.err, s)) << r.err;
  EXPECT_FALSE(fs::exists(path("heat.png")));  // nothing written on bad input
}

TEST_F(SssCompare, MissingAndCorruptFilesAreNamed) {
  write_png(path("a.png"), texture(8, 8));
  std::ofstream(path("corrupt.png"), std::ios::binary) << "\x89PNG\r\n\x1a\n garbage";
  std::ofstream(path("corrupt.exr"), std::ios::binary) << std::string("\x76\x2f\x31\x01", 4) << "junkjunkjunk";
  std::ofstream(path("text.png")) << "not an image at all";
  for (const std::string& bad : {path("missing.png"), path("corrupt.png"), path("corrupt.exr"), path("text.png")}) {
    for (const std::string& args : {path("a.png") + " " + bad, bad + " " + path("a.png")}) {
      const CliRun r = run(args + " --json");
      EXPECT_EQ(r.code, 2) << args;
      EXPECT_TRUE(r.out.empty()) << r.out;
      EXPECT_TRUE(contains(r.err, bad)) << r.err;
    }
  }
}

TEST_F(SssCompare, NoCommonGeometryIsBadInput) {
  Pixels a = texture(8, 8), b = texture(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) (x < 4 ? a : b).at(x, y)[3] = 0.0f;
  write_png(path("a.png"), a);
  write_png(path("b.png"), b);
  const CliRun r = run(path("a.png") + " " + path("b.png"));
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "no pixel to compare")) << r.err;
  EXPECT_TRUE(contains(r.err, path("a.png") + " has geometry (alpha > 0.5) in 32 pixels")) << r.err;
}

TEST_F(SssCompare, NonFiniteValuesAreNamed) {
  Pixels a = texture(8, 8);
  a.at(3, 5)[1] = std::numeric_limits<float>::quiet_NaN();
  write_exr(path("nan.exr"), a);
  write_exr(path("b.exr"), texture(8, 8));
  const CliRun r = run(path("nan.exr") + " " + path("b.exr"));
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, path("nan.exr") + ": pixel (3, 5)")) << r.err;
  // In the background it does not matter.
  a.at(3, 5)[3] = 0.0f;
  write_exr(path("nan.exr"), a);
  EXPECT_EQ(run(path("nan.exr") + " " + path("b.exr")).code, 0);
}

TEST_F(SssCompare, BadUsageExitsTwoAndNamesTheOption) {
  write_png(path("a.png"), texture(8, 8));
  const std::string aa = path("a.png") + " " + path("a.png") + " ";
  struct Case {
    std::string args, named;
  };
  for (const Case& c : {Case{"", "A"}, Case{path("a.png"), "B"}, Case{aa + "--bogus", "--bogus"},
                        Case{aa + "--tolerance -1", "--tolerance"}, Case{aa + "--tolerance abc", "--tolerance"},
                        Case{aa + "--threshold nan", "--threshold"}, Case{aa + "--max-abs -0.1", "--max-abs"},
                        Case{aa + "--max-fraction 2", "--max-fraction"}, Case{aa + "--min-ssim 3", "--min-ssim"},
                        Case{aa + "--exposure 0", "--exposure"},
                        Case{aa + "--heatmap " + path("h.png") + " --heatmap-max 0", "--heatmap-max"},
                        Case{aa + "--heatmap-max 1", "--heatmap"},
                        Case{aa + "--heatmap " + path("h.jpg"), "--heatmap"}}) {
    const CliRun r = run(c.args + " --json");
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_TRUE(r.out.empty()) << c.args << r.out;
    EXPECT_TRUE(contains(r.err, c.named)) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(path("h.png")));
  EXPECT_FALSE(fs::exists(path("h.jpg")));
}

#endif  // SSS_COMPARE_EXE
