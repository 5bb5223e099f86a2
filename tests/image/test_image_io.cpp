#include "renderer/image/AtomicFile.h"
#include "renderer/image/Image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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
