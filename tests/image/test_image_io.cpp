#include "image/AtomicFile.h"
#include "image/Image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fs = std::filesystem;
using namespace sss::image;

namespace {
fs::path dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path p = fs::temp_directory_path() / ("sss-image-" + std::to_string(::getpid()) + "-" + info->name());
  fs::create_directories(p);
  return p;
}
Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      p[0] = x / float(w - 1);
      p[1] = y / float(h - 1);
      p[2] = 3.5f * (x + y);  // HDR values survive in EXR
      p[3] = 1.0f;
    }
  return img;
}
void write_bytes(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }
}  // namespace

TEST(ImageIo, ExrRoundTripIsExact) {
  const Image img = gradient(17, 9);
  const fs::path p = dir() / "a.exr";
  write_exr(p.string(), img);
  auto back = read_image(p.string());
  ASSERT_TRUE(std::holds_alternative<Image>(back)) << std::get<ImageError>(back).what();
  const Image& b = std::get<Image>(back);
  ASSERT_EQ(b.width, 17);
  ASSERT_EQ(b.height, 9);
  for (std::size_t i = 0; i < img.rgba.size(); ++i) EXPECT_EQ(b.rgba[i], img.rgba[i]) << i;
}

TEST(ImageIo, PngRoundTripWithinOneCode) {
  const Image img = gradient(31, 7);
  const fs::path p = dir() / "a.png";
  write_image(p.string(), img);
  auto back = read_image(p.string());
  ASSERT_TRUE(std::holds_alternative<Image>(back));
  const Image& b = std::get<Image>(back);
  for (std::size_t i = 0; i < img.rgba.size(); ++i)
    EXPECT_NEAR(b.rgba[i], std::clamp(img.rgba[i], 0.0f, 1.0f), 0.5f / 255.0f + 1e-6f);
}

TEST(ImageIo, SrgbTransferFunction) {
  // IEC 61966-2-1 reference points.
  EXPECT_FLOAT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgb_encode(1.0f), 1.0f);
  EXPECT_NEAR(srgb_encode(0.18f), 0.4614f, 1e-4f);
  for (float v : {0.001f, 0.01f, 0.2f, 0.7f}) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-6f);
}

TEST(ImageIo, BadFilesNameThePath) {
  const fs::path d = dir();
  const std::string png_magic = "\x89PNG\r\n\x1a\n";
  const std::string exr_magic = std::string("\x76\x2f\x31\x01", 4);
  const std::pair<const char*, std::string> cases[] = {
      {"empty.png", ""},
      {"text.png", "hello, this is not an image"},
      {"truncated.png", png_magic + "\0\0\0\rIHDR"},
      {"truncated.exr", exr_magic + std::string(20, '\0')},
  };
  for (const auto& [name, bytes] : cases) {
    write_bytes(d / name, bytes);
    auto r = read_image((d / name).string());
    ASSERT_TRUE(std::holds_alternative<ImageError>(r)) << name;
    EXPECT_NE(std::get<ImageError>(r).what().find(name), std::string::npos);
  }
  auto missing = read_image((d / "missing.exr").string());
  ASSERT_TRUE(std::holds_alternative<ImageError>(missing));
}

TEST(ImageIo, UnknownExtensionAndBadImagesAreRefusedWithoutOutput) {
  const fs::path d = dir();
  EXPECT_THROW(write_image((d / "a.jpg").string(), gradient(4, 4)), WriteError);
  EXPECT_THROW(write_png((d / "z.png").string(), Image(0, 0)), WriteError);
  EXPECT_FALSE(fs::exists(d / "a.jpg"));
  EXPECT_FALSE(fs::exists(d / "z.png"));
}

// What read_image refuses before a third-party decoder runs (each was a fuzzing finding
// on Debian's stb_image / tinyexr 1.0.1: fuzz/regressions/image/).
namespace {
std::string read_error(const fs::path& p) {
  auto r = read_image(p.string());
  return std::holds_alternative<ImageError>(r) ? std::get<ImageError>(r).what() : std::string("loaded");
}
std::string slurp_bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}
}  // namespace

TEST(ImageIo, PngChunkPastTheEndIsRefusedBeforeDecoding) {
  // A valid 1x1 PNG whose IDAT claims 2^31 - 1 bytes: stb_image would grow its buffer
  // to that size before finding the bytes missing.
  const fs::path ok = dir() / "ok.png";
  Image one(1, 1);
  write_png(ok.string(), one);
  std::string bytes = slurp_bytes(ok);
  const std::size_t idat = bytes.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  bytes.replace(idat - 4, 4, std::string("\x7f\xff\xff\xff", 4));
  const fs::path bad = dir() / "bad.png";
  write_bytes(bad, bytes);
  EXPECT_NE(read_error(bad).find("IDAT at byte"), std::string::npos) << read_error(bad);
  EXPECT_NE(read_error(bad).find("past the end of the file"), std::string::npos);
  // Cut before IEND: also refused, by the same walk.
  write_bytes(bad, slurp_bytes(ok).substr(0, slurp_bytes(ok).size() - 12));
  EXPECT_NE(read_error(bad).find("no IEND"), std::string::npos) << read_error(bad);
}

TEST(ImageIo, ExrHeadersTinyexrCannotReadSafelyAreRefused) {
  const fs::path ok = dir() / "ok.exr";
  write_exr(ok.string(), gradient(4, 3));
  const std::string good = slurp_bytes(ok);
  ASSERT_TRUE(std::holds_alternative<Image>(read_image(ok.string())));
  const fs::path bad = dir() / "bad.exr";
  // The tiled bit of the version field (byte 5, 0x02).
  std::string tiled = good;
  tiled[5] = char(tiled[5] | 0x02);
  write_bytes(bad, tiled);
  EXPECT_NE(read_error(bad).find("tiled EXR files are not read"), std::string::npos) << read_error(bad);
  // PIZ (4) instead of ZIP: "compression\0compression\0" + int32 size 1 + the byte.
  const std::string key("compression\0compression\0", 24);
  const std::size_t at = good.find(key);
  ASSERT_NE(at, std::string::npos);
  std::string piz = good;
  piz[at + key.size() + 4] = 4;
  write_bytes(bad, piz);
  EXPECT_NE(read_error(bad).find("EXR compression PIZ is not read"), std::string::npos) << read_error(bad);
  // A dataWindow whose corners overflow an int: refused on size, in 64 bits.
  const std::string window("dataWindow\0box2i\0", 17);
  const std::size_t w = good.find(window);
  ASSERT_NE(w, std::string::npos);
  std::string huge = good;
  huge.replace(w + window.size() + 4, 4, std::string("\x00\x00\x00\x80", 4));  // min_x = INT_MIN
  huge.replace(w + window.size() + 12, 4, std::string("\xff\xff\xff\x7f", 4));  // max_x = INT_MAX
  write_bytes(bad, huge);
  EXPECT_NE(read_error(bad).find("EXR size out of range"), std::string::npos) << read_error(bad);
}
