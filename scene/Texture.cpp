#include "scene/Texture.h"

#include "image/Image.h"

#include <stb_image.h>

#include <climits>
#include <cstring>

namespace sss::scene {

namespace {

std::optional<std::string> check_size(std::uint64_t w, std::uint64_t h, const ImageLimits& limits) {
  if (w == 0 || h == 0) return std::string("has a zero size");
  if (w > limits.max_side || h > limits.max_side || w * h > limits.max_pixels)
    return "is " + std::to_string(w) + "x" + std::to_string(h) + ", larger than the limit (" +
           std::to_string(limits.max_side) + " per side, " + std::to_string(limits.max_pixels) +
           " pixels)";
  return std::nullopt;
}

}  // namespace

std::string_view image_media_type(std::span<const unsigned char> bytes) {
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image/jpeg";
  return {};
}

std::variant<ImageRgba8, std::string> decode_image(std::span<const unsigned char> bytes,
                                                   const ImageLimits& limits) {
  if (bytes.empty()) return std::string("has no bytes");
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) return std::string("is larger than 2 GiB");
  // glTF allows PNG and JPEG only; stb_image's other decoders are never reached.
  if (image_media_type(bytes).empty()) return std::string("is neither PNG nor JPEG (the formats glTF allows)");
  // A PNG's size is read from its IHDR (PNG spec §5.3, §11.2.2: the first chunk, width
  // and height big-endian at bytes 16 and 20) before stb_image sees it: stb refuses
  // w * h * 4 > 2^30 in its header pass with a message that does not say why.
  if (image_media_type(bytes) == "image/png" && bytes.size() >= 24 &&
      std::memcmp(bytes.data() + 12, "IHDR", 4) == 0) {
    const auto be32 = [&](std::size_t at) {
      return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 |
             std::uint32_t(bytes[at + 2]) << 8 | std::uint32_t(bytes[at + 3]);
    };
    if (auto e = check_size(be32(16), be32(20), limits)) return *e;
  }
  if (image_media_type(bytes) == "image/png")
    if (std::string why = image::check_png_chunks(bytes); !why.empty()) return why;
  const int len = static_cast<int>(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &channels))
    return std::string("is not a PNG or JPEG image stb_image can read: ") + stbi_failure_reason();
  if (w <= 0 || h <= 0) return std::string("has a zero size");
  if (auto e = check_size(std::uint64_t(w), std::uint64_t(h), limits)) return *e;
  int dw = 0, dh = 0;
  stbi_uc* data = stbi_load_from_memory(bytes.data(), len, &dw, &dh, &channels, 4);
  if (!data) return std::string("cannot be decoded: ") + stbi_failure_reason();
  if (dw != w || dh != h) {
    stbi_image_free(data);
    return std::string("decoded to a different size than its header");
  }
  ImageRgba8 img;
  img.width = static_cast<std::uint32_t>(w);
  img.height = static_cast<std::uint32_t>(h);
  img.pixels.resize(std::size_t(w) * std::size_t(h) * 4);
  std::memcpy(img.pixels.data(), data, img.pixels.size());
  stbi_image_free(data);
  return img;
}

std::optional<Wrap> wrap_from_gl(int gl) {
  switch (gl) {
    case -1:
    case 10497: return Wrap::Repeat;
    case 33071: return Wrap::ClampToEdge;
    case 33648: return Wrap::MirroredRepeat;
    default: return std::nullopt;
  }
}

std::optional<Sampler> sampler_from_gl(int mag, int min, int wrap_s, int wrap_t) {
  Sampler s;
  const auto ws = wrap_from_gl(wrap_s), wt = wrap_from_gl(wrap_t);
  if (!ws || !wt) return std::nullopt;
  s.wrap_s = *ws;
  s.wrap_t = *wt;
  switch (mag) {
    case -1:
    case 9729: s.mag = Filter::Linear; break;
    case 9728: s.mag = Filter::Nearest; break;
    default: return std::nullopt;
  }
  switch (min) {
    case -1:
    case 9987: s.min = Filter::Linear; s.mip = Filter::Linear; break;  // LINEAR_MIPMAP_LINEAR
    case 9728: s.min = Filter::Nearest; s.mipmaps = false; break;      // NEAREST
    case 9729: s.min = Filter::Linear; s.mipmaps = false; break;       // LINEAR
    case 9984: s.min = Filter::Nearest; s.mip = Filter::Nearest; break;  // NEAREST_MIPMAP_NEAREST
    case 9985: s.min = Filter::Linear; s.mip = Filter::Nearest; break;   // LINEAR_MIPMAP_NEAREST
    case 9986: s.min = Filter::Nearest; s.mip = Filter::Linear; break;   // NEAREST_MIPMAP_LINEAR
    default: return std::nullopt;
  }
  return s;
}

}  // namespace sss::scene
