#include "renderer/image/Image.h"

#include "renderer/image/AtomicFile.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>

namespace sss::image {

namespace {

bool has_suffix(std::string s, const char* suffix) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  const std::size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

bool check_size(int w, int h) {
  return w > 0 && h > 0 && w <= kMaxImageSide && h <= kMaxImageSide &&
         static_cast<std::size_t>(w) * static_cast<std::size_t>(h) <= kMaxImagePixels;
}

void require_writable(const std::string& path, const Image& img) {
  if (!check_size(img.width, img.height) ||
      img.rgba.size() != static_cast<std::size_t>(img.width) * img.height * 4)
    throw WriteError(path + ": invalid image of " + std::to_string(img.width) + "x" +
                     std::to_string(img.height));
}

}  // namespace

float srgb_encode(float v) {
  if (!(v > 0.0f)) return 0.0f;
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float v) {
  if (!(v > 0.0f)) return 0.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

Image encode_srgb(const Image& linear) {
  Image out = linear;
  for (std::size_t i = 0; i < out.rgba.size(); ++i)
    if (i % 4 != 3) out.rgba[i] = srgb_encode(out.rgba[i]);
  return out;
}

std::variant<Image, ImageError> read_image(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return ImageError{path, "cannot open the file"};
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), {});
  if (bytes.size() < 8) return ImageError{path, "too short to be a PNG or EXR image"};
  if (bytes.size() > (std::size_t{1} << 31)) return ImageError{path, "file larger than 2 GiB"};
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  if (std::memcmp(bytes.data(), kPng, 8) == 0) {
    int w = 0, h = 0, comp = 0;
    const int len = static_cast<int>(bytes.size());
    if (!stbi_info_from_memory(bytes.data(), len, &w, &h, &comp) || !check_size(w, h))
      return ImageError{path, "unsupported or corrupt PNG header"};
    std::unique_ptr<stbi_uc, void (*)(void*)> data(
        stbi_load_from_memory(bytes.data(), len, &w, &h, &comp, 4), stbi_image_free);
    if (!data) return ImageError{path, std::string("corrupt PNG: ") + stbi_failure_reason()};
    Image img(w, h);
    for (std::size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = data.get()[i] / 255.0f;
    return img;
  }
  if (std::memcmp(bytes.data(), kExr, 4) == 0) {
    EXRVersion version;
    EXRHeader header;
    InitEXRHeader(&header);
    const char* err = nullptr;
    if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
      return ImageError{path, "corrupt EXR version field"};
    if (ParseEXRHeaderFromMemory(&header, &version, bytes.data(), bytes.size(), &err) !=
        TINYEXR_SUCCESS) {
      std::string msg = err ? err : "corrupt EXR header";
      FreeEXRErrorMessage(err);
      return ImageError{path, msg};
    }
    const int w = header.data_window.max_x - header.data_window.min_x + 1;
    const int h = header.data_window.max_y - header.data_window.min_y + 1;
    FreeEXRHeader(&header);
    if (!check_size(w, h)) return ImageError{path, "EXR size out of range"};
    float* out = nullptr;
    int ow = 0, oh = 0;
    if (LoadEXRFromMemory(&out, &ow, &oh, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) {
      std::string msg = err ? err : "corrupt EXR";
      FreeEXRErrorMessage(err);
      return ImageError{path, msg};
    }
    std::unique_ptr<float, void (*)(void*)> owned(out, std::free);
    if (!check_size(ow, oh)) return ImageError{path, "EXR size out of range"};
    Image img(ow, oh);
    std::memcpy(img.rgba.data(), out, img.rgba.size() * sizeof(float));
    return img;
  }
  return ImageError{path, "not a PNG or OpenEXR file"};
}

void write_png(const std::string& path, const Image& img) {
  require_writable(path, img);
  std::vector<unsigned char> px(img.rgba.size());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const float v = std::isfinite(img.rgba[i]) ? std::clamp(img.rgba[i], 0.0f, 1.0f) : 0.0f;
    px[i] = static_cast<unsigned char>(std::lround(v * 255.0f));
  }
  std::string encoded;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size);
  };
  if (!stbi_write_png_to_func(sink, &encoded, img.width, img.height, 4, px.data(), img.width * 4))
    throw WriteError(path + ": PNG encoding failed");
  write_file_atomically(path, encoded);
}

void write_exr(const std::string& path, const Image& img) {
  require_writable(path, img);
  // Planar channels in the order OpenEXR readers expect: A, B, G, R (alphabetical).
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  std::vector<float> planes[4];
  for (auto& p : planes) p.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) planes[c][i] = img.rgba[i * 4 + c];
  float* channel_ptrs[4] = {planes[3].data(), planes[2].data(), planes[1].data(), planes[0].data()};
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = 4;
  image.images = reinterpret_cast<unsigned char**>(channel_ptrs);
  image.width = img.width;
  image.height = img.height;
  EXRChannelInfo channels[4];
  std::memset(channels, 0, sizeof channels);
  const char* names[4] = {"A", "B", "G", "R"};
  int pixel_types[4], requested[4];
  for (int c = 0; c < 4; ++c) {
    std::strncpy(channels[c].name, names[c], 255);
    pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
    requested[c] = TINYEXR_PIXELTYPE_FLOAT;  // 32-bit: goldens compare exactly
  }
  header.num_channels = 4;
  header.channels = channels;
  header.pixel_types = pixel_types;
  header.requested_pixel_types = requested;
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0 || !memory) {
    const std::string msg = err ? err : "EXR encoding failed";
    FreeEXRErrorMessage(err);
    throw WriteError(path + ": " + msg);
  }
  std::unique_ptr<unsigned char, void (*)(void*)> owned(memory, std::free);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(memory), size));
}

void write_image(const std::string& path, const Image& img) {
  if (has_suffix(path, ".png")) return write_png(path, img);
  if (has_suffix(path, ".exr")) return write_exr(path, img);
  throw WriteError(path + ": unknown image type (use .png or .exr)");
}

}  // namespace sss::image
