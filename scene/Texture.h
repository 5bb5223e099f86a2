// Texture: a decoded RGBA8 image and how to sample it (glTF sampler). Pixels are stored
// as written in the file, top row first; the material says how to interpret them
// (base colour: sRGB; normal map: linear). Several textures may share one image.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace sss::scene {

struct ImageRgba8 {
  std::string name;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4, rows top to bottom
};

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Nearest, Linear };

struct Sampler {
  Wrap wrap_s = Wrap::Repeat;  // glTF defaults
  Wrap wrap_t = Wrap::Repeat;
  Filter mag = Filter::Linear;
  Filter min = Filter::Linear;
  bool mipmaps = true;             // minFilter *_MIPMAP_* or unspecified
  Filter mip = Filter::Linear;     // between mip levels
};

struct Texture {
  std::string name;
  std::shared_ptr<const ImageRgba8> image;
  Sampler sampler;
};

struct ImageLimits {
  std::uint32_t max_side = 16384;            // lavapipe's max 2D image (DESIGN.md §9)
  std::uint64_t max_pixels = 64ull << 20;    // 256 MiB decoded
};

// "image/png" or "image/jpeg" from the bytes' signature (PNG: the 8-byte signature of
// PNG §5.2; JPEG: SOI FF D8 then a marker FF); empty for anything else.
std::string_view image_media_type(std::span<const unsigned char> bytes);

// Decodes PNG or JPEG bytes (stb_image) into RGBA8. The header is read first and the
// size checked against `limits` before any pixel is decoded. Returns a message on
// failure (unknown format, corrupt data, too large).
std::variant<ImageRgba8, std::string> decode_image(std::span<const unsigned char> bytes,
                                                   const ImageLimits& limits);

// glTF sampler enums (33071 CLAMP_TO_EDGE, 9729 LINEAR, ...); nullopt for a value that
// is not one of them. -1 means "not given" and yields the default.
std::optional<Wrap> wrap_from_gl(int gl);
std::optional<Sampler> sampler_from_gl(int mag, int min, int wrap_s, int wrap_t);

}  // namespace sss::scene
