// An RGBA float image and its files. PNG (8-bit, via stb) and OpenEXR (32-bit float,
// via tinyexr). Writes go through write_file_atomically: a failed write leaves nothing.
//
// Colour (DESIGN.md §3): EXR holds linear values as they are. PNG holds display values:
// write_png quantizes what it is given (the caller tonemaps and sRGB-encodes first, see
// encode_srgb), and read_png returns the 8-bit codes divided by 255, not linearized.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace sss::image {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgba;  // row-major, top row first, 4 floats per pixel
  // Named text fields: written into an EXR header as string attributes (in this order)
  // and read back from one (every string attribute that is not OpenEXR's own); PNG
  // files carry none.
  std::vector<std::pair<std::string, std::string>> attributes;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(static_cast<std::size_t>(w) * h * 4, 0.0f) {}
  float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
};

struct ImageError {
  std::string path;
  std::string message;
  std::string what() const { return path + ": " + message; }
};

// Largest accepted side and pixel count when reading (a hostile header cannot make us
// allocate gigabytes).
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;

// By file contents (PNG or EXR magic), whatever the extension.
std::variant<Image, ImageError> read_image(const std::string& path);

// The PNG's chunks, walked before a decoder sees them: each must lie inside the bytes, up
// to IEND (stb_image grows its buffer to a chunk's declared length before checking that
// the bytes exist). An empty string when they do, else what is wrong.
std::string check_png_chunks(std::span<const unsigned char> png);

// Throw WriteError (AtomicFile.h) on failure; values are clamped to [0, 1] and rounded.
void write_png(const std::string& path, const Image& image);
void write_exr(const std::string& path, const Image& image);
// Chooses by extension (.png or .exr, case-insensitive); anything else is an error.
void write_image(const std::string& path, const Image& image);

// The sRGB transfer function (IEC 61966-2-1) applied to R, G, B; alpha unchanged.
float srgb_encode(float linear);
float srgb_decode(float encoded);
Image encode_srgb(const Image& linear);

// a with b's R, G, B taken off, alpha and attributes a's: a frame less its specular (the
// error budget's scattered light). Throws std::invalid_argument when the sizes differ.
Image subtract_rgb(const Image& a, const Image& b);

// Premultiplied to straight alpha in place, for 8-bit codes / 255: R, G, B divided by
// alpha where 0 < alpha < 1, at most 1, and rounded to the nearest code (so the image is
// what a PNG of it holds); pixels with alpha 0 or 1 are unchanged. The anti-aliased display
// image is premultiplied (the frame over black, alpha its coverage); a PNG is straight.
void unpremultiply(Image& image);

}  // namespace sss::image
