#include "image/Image.h"

#include "image/AtomicFile.h"
#include "shaders/shared/tonemap.h"

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
#include <span>
#include <stdexcept>
#include <string>

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

// Walks an OpenEXR header before tinyexr sees it: Debian's tinyexr 1.0.1 asserts (aborts
// the process) on some hostile headers, e.g. an unknown value of the "type" attribute
// (tinyexr.h ConvertHeader; found by fuzzing, fuzz/regressions/image/). The layout is the
// OpenEXR file format's ("The OpenEXR File Layout", openexr.com): magic 20000630, a 4-byte
// version field (low byte 2; bit 0x200 tiled, 0x400 long names, 0x800 deep data, 0x1000
// multi-part), then attributes (name NUL, type name NUL, int32 little-endian size, value)
// up to an empty name. Only single-part, non-deep files are read here. Returns an error
// message, or an empty string when the header is well formed; width and height come from
// its dataWindow, computed in 64 bits.
std::int32_t le32(const unsigned char* p) {
  return std::int32_t(std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                      std::uint32_t(p[3]) << 24);
}

// What check_exr_header learns from the attributes it reads.
struct ExrHeaderFacts {
  std::int64_t width = 0, height = 0;
  bool have_window = false;
  int compression = 0;            // NONE when absent
  std::int64_t chunk_count = -1;  // absent
};

// One attribute of the header: an error, or empty (and what it says in `facts`).
std::string check_exr_attribute(const std::string& name, const std::string& type,
                                const unsigned char* value, std::int32_t size,
                                ExrHeaderFacts& facts) {
  if (name == "type") {
    // The value up to its first NUL, as tinyexr reads it.
    const std::string v(std::string(reinterpret_cast<const char*>(value), std::size_t(size)).c_str());
    if (type != "string" || v != "scanlineimage")
      return "EXR header attribute type: \"" + v + "\" (only scanlineimage is read)";
  } else if (name == "tiles") {
    return "EXR header attribute tiles: tiled EXR files are not read (re-save it as scanlines)";
  } else if (name == "chunkCount") {
    if (type != "int" || size != 4) return "EXR header attribute chunkCount: not an int";
    facts.chunk_count = le32(value);
  } else if (name == "compression") {
    // NONE, RLE, ZIPS, ZIP only. tinyexr 1.0.1's PIZ decoder reads past its buffer on
    // malformed data (found by fuzzing, fuzz/regressions/image/exr_piz_read_overflow.exr),
    // and the others (PXR24, B44, DWA) it does not decode at all.
    if (type != "compression" || size != 1) return "EXR header attribute compression: not a compression";
    static const char* const kNames[] = {"none", "RLE", "ZIPS", "ZIP", "PIZ", "PXR24", "B44", "B44A", "DWAA", "DWAB"};
    if (value[0] > 3)
      return std::string("EXR compression ") + (value[0] < 10 ? kNames[value[0]] : std::to_string(value[0]).c_str()) +
             " is not read (only none, RLE, ZIPS and ZIP; re-save the file with ZIP)";
    facts.compression = value[0];
  } else if (name == "dataWindow") {
    if (type != "box2i" || size != 16) return "EXR header attribute dataWindow: not a box2i";
    const std::int64_t x0 = le32(value), y0 = le32(value + 4), x1 = le32(value + 8),
                       y1 = le32(value + 12);
    facts.width = x1 - x0 + 1;
    facts.height = y1 - y0 + 1;
    facts.have_window = true;
  }
  return {};
}

std::string check_exr_header(const std::vector<unsigned char>& b, std::int64_t& width,
                             std::int64_t& height) {
  if (b.size() < 8) return "truncated EXR header";
  const std::uint32_t field = std::uint32_t(le32(&b[4]));
  if ((field & 0xff) != 2) return "EXR version " + std::to_string(field & 0xff) + " (only 2 is read)";
  if (field & 0x1800) return "multi-part and deep EXR files are not read";
  // Tiled files are refused too: tinyexr 1.0.1 asserts or divides by zero on malformed tile
  // descriptions (a "tiles" size other than 9, level mode 3, tile size 0, a "type" that
  // contradicts the tiled bit) and loses a failed tiled decode's buffers. write_exr and
  // the renderers this project is compared with write scanline files.
  if (field & 0x200) return "tiled EXR files are not read (re-save it as scanlines)";
  const std::size_t max_name = (field & 0x400) ? 255 : 31;
  auto read_cstr = [&](std::size_t& at, std::string& out) {
    const std::size_t end = std::min(b.size(), at + max_name + 1);
    for (std::size_t i = at; i < end; ++i)
      if (b[i] == 0) {
        out.assign(reinterpret_cast<const char*>(&b[at]), i - at);
        at = i + 1;
        return true;
      }
    return false;
  };
  std::size_t at = 8;
  ExrHeaderFacts facts;
  for (int count = 0;; ++count) {
    if (count > 1024) return "EXR header has more than 1024 attributes";
    std::string name, type;
    if (!read_cstr(at, name)) return "EXR header attribute name is not terminated";
    if (name.empty()) break;
    if (!read_cstr(at, type)) return "EXR header attribute " + name + ": type name is not terminated";
    if (b.size() - at < 4) return "EXR header attribute " + name + ": truncated";
    const std::int32_t size = le32(&b[at]);
    at += 4;
    if (size < 0 || std::size_t(size) > b.size() - at)
      return "EXR header attribute " + name + ": size " + std::to_string(size) + " past the end";
    if (std::string e = check_exr_attribute(name, type, b.data() + at, size, facts); !e.empty())
      return e;
    at += std::size_t(size);
  }
  if (!facts.have_window) return "EXR header has no dataWindow";
  width = facts.width;
  height = facts.height;
  // tinyexr sizes its offset table by chunkCount before checking it against the file (a
  // 300-byte file could ask for 16 GiB): it must be the count the image has, one block
  // per scanline for none/RLE/ZIPS and per 16 for ZIP (OpenEXR file layout).
  if (facts.chunk_count != -1 && height > 0) {
    const std::int64_t lines = facts.compression == 3 ? 16 : 1;
    const std::int64_t expected = (height + lines - 1) / lines;
    if (facts.chunk_count != expected)
      return "EXR header attribute chunkCount: " + std::to_string(facts.chunk_count) +
             ", the image has " + std::to_string(expected) + " blocks";
  }
  return {};
}

}  // namespace

// Walks a PNG's chunks (PNG spec §5.3: 4-byte big-endian length, 4-byte type, data, CRC)
// before stb_image sees them: stb grows its IDAT buffer to a chunk's declared length
// before checking that the bytes exist, so a 70-byte file could make it allocate 2 GiB
// (found by fuzzing, fuzz/regressions/image/png_idat_length_past_end.png). Every chunk
// must lie inside the file, up to IEND.
std::string check_png_chunks(std::span<const unsigned char> b) {
  if (b.size() < 8) return "too short to be a PNG";
  std::size_t at = 8;
  while (true) {
    if (b.size() - at < 12) return "PNG chunk at byte " + std::to_string(at) + " is truncated (no IEND)";
    const std::uint32_t length = std::uint32_t(b[at]) << 24 | std::uint32_t(b[at + 1]) << 16 |
                                 std::uint32_t(b[at + 2]) << 8 | std::uint32_t(b[at + 3]);
    const std::string type(reinterpret_cast<const char*>(b.data() + at + 4), 4);
    if (length > b.size() - at - 12)
      return "PNG chunk " + type + " at byte " + std::to_string(at) + " claims " +
             std::to_string(length) + " bytes, past the end of the file";
    at += 12 + std::size_t(length);
    if (type == "IEND") return {};
  }
}

float srgb_encode(float v) {
  if (!(v > 0.0f)) return 0.0f;
  return v <= SSS_SRGB_ENCODE_CUTOFF ? SSS_SRGB_LINEAR_SLOPE * v
                                     : SSS_SRGB_SCALE * std::pow(v, 1.0f / SSS_SRGB_GAMMA) - SSS_SRGB_OFFSET;
}

float srgb_decode(float v) {
  if (!(v > 0.0f)) return 0.0f;
  return v <= SSS_SRGB_DECODE_CUTOFF ? v / SSS_SRGB_LINEAR_SLOPE
                                     : std::pow((v + SSS_SRGB_OFFSET) / SSS_SRGB_SCALE, SSS_SRGB_GAMMA);
}

Image encode_srgb(const Image& linear) {
  Image out = linear;
  for (std::size_t i = 0; i < out.rgba.size(); ++i)
    if (i % 4 != 3) out.rgba[i] = srgb_encode(out.rgba[i]);
  return out;
}

Image subtract_rgb(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("subtract_rgb: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " less " + std::to_string(b.width) + "x" + std::to_string(b.height));
  Image out = a;
  for (std::size_t i = 0; i < out.rgba.size(); ++i)
    if (i % 4 != 3) out.rgba[i] -= b.rgba[i];
  return out;
}

void unpremultiply(Image& image) {
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    const float a = image.rgba[i + 3];
    if (!(a > 0.0f && a < 1.0f)) continue;
    for (std::size_t c = 0; c < 3; ++c)
      image.rgba[i + c] = std::round(std::min(image.rgba[i + c] / a, 1.0f) * 255.0f) / 255.0f;
  }
}

namespace {

// The image of a PNG file's bytes (8-bit RGBA, scaled to [0, 1]), or why not.
std::variant<Image, ImageError> decode_png(const std::vector<unsigned char>& bytes, const std::string& path) {
  if (std::string why = check_png_chunks(bytes); !why.empty()) return ImageError{path, why};
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

// The image of an OpenEXR file's bytes (scanline, HALF/FLOAT/UINT channels; R, G, B and
// optionally A, or one gray channel) with its string attributes, or why not.
// The decoded channels into img's RGBA: idx[k] is the channel of R, G, B, A (-1: none),
// or a one-channel image is grey.
void copy_exr_pixels(const EXRHeader& header, const EXRImage& exr, const int (&idx)[4], bool gray,
                     Image& img) {
  // One sample of channel c (tinyexr allocates every channel at full size, whatever its
  // sampling) at pixel i; HALF was decoded as FLOAT, UINT is converted.
  auto sample = [&](int c, std::size_t i) -> float {
    if (header.requested_pixel_types[c] == TINYEXR_PIXELTYPE_UINT)
      return static_cast<float>(reinterpret_cast<const std::uint32_t*>(exr.images[c])[i]);
    return reinterpret_cast<const float*>(exr.images[c])[i];
  };
  const std::size_t n = std::size_t(exr.width) * std::size_t(exr.height);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) img.rgba[4 * i + k] = sample(gray ? 0 : idx[k], i);
    img.rgba[4 * i + 3] = gray || idx[3] < 0 ? 1.0f : sample(idx[3], i);  // no alpha: opaque
  }
}

// The header's string attributes, in img.attributes.
void copy_string_attributes(const EXRHeader& header, Image& img) {
  for (int a = 0; a < header.num_custom_attributes; ++a) {
    const EXRAttribute& attr = header.custom_attributes[a];
    if (std::strcmp(attr.type, "string") != 0 || attr.size < 0 || !attr.value) continue;
    // A string attribute is its bytes (OpenEXR writes no terminator; some writers do).
    std::string value(reinterpret_cast<const char*>(attr.value), std::size_t(attr.size));
    if (const auto nul = value.find('\0'); nul != std::string::npos) value.resize(nul);
    img.attributes.emplace_back(attr.name, value);
  }
}

// The header's R, G, B and A channels into idx (-1 where absent); HALF channels are asked
// for as FLOAT.
void find_rgba_channels(EXRHeader& header, int (&idx)[4]) {
  static const char* const kNames[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < header.num_channels; ++c) {
    for (int k = 0; k < 4; ++k)
      if (std::strcmp(header.channels[c].name, kNames[k]) == 0) idx[k] = c;
    if (header.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
  }
}

std::variant<Image, ImageError> decode_exr(const std::vector<unsigned char>& bytes, const std::string& path) {
  // dataWindow's max - min + 1 of hostile 32-bit corners overflows an int: in 64 bits
  // (found by fuzzing, fuzz/regressions/image/exr_data_window_int_overflow.exr).
  std::int64_t w64 = 0, h64 = 0;
  if (std::string why = check_exr_header(bytes, w64, h64); !why.empty())
    return ImageError{path, why};
  if (w64 <= 0 || h64 <= 0 || w64 > kMaxImageSide || h64 > kMaxImageSide ||
      !check_size(static_cast<int>(w64), static_cast<int>(h64)))
    return ImageError{path, "EXR size out of range"};
  // Not LoadEXRFromMemory: tinyexr 1.0.1's convenience loader leaks the header and the
  // image whenever decoding fails or a channel is missing (found by fuzzing,
  // fuzz/regressions/image/exr_load_image_failure_leak.exr) and reads a UINT channel's
  // bits as floats. The header and image are owned here and freed on every path.
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
    return ImageError{path, "corrupt EXR version field"};
  EXRHeader header;
  InitEXRHeader(&header);
  std::unique_ptr<EXRHeader, int (*)(EXRHeader*)> header_owner(&header, FreeEXRHeader);
  const char* err = nullptr;
  auto fail = [&](const char* fallback) {
    std::string msg = err ? err : fallback;
    if (err) FreeEXRErrorMessage(err);
    return ImageError{path, msg};
  };
  // A failed parse may have filled part of the header: the owner frees it (fuzzing).
  if (ParseEXRHeaderFromMemory(&header, &version, bytes.data(), bytes.size(), &err) !=
      TINYEXR_SUCCESS)
    return fail("corrupt EXR header");
  int idx[4] = {-1, -1, -1, -1};  // R, G, B, A
  find_rgba_channels(header, idx);
  const bool gray = header.num_channels == 1;
  if (!gray && (idx[0] < 0 || idx[1] < 0 || idx[2] < 0))
    return ImageError{path, "EXR has no R, G and B channels (and is not one-channel)"};
  EXRImage exr;
  InitEXRImage(&exr);
  std::unique_ptr<EXRImage, int (*)(EXRImage*)> image_owner(&exr, FreeEXRImage);
  // tinyexr frees a failed decode's image itself (DecodeEXRImage calls FreeEXRImage,
  // without clearing the pointers: freeing it again here was a double free), but it sets
  // num_channels only on success, so its FreeEXRImage would free the channel array and
  // lose the channel buffers (both found by fuzzing,
  // fuzz/regressions/image/exr_decode_failure_double_free.exr). Set beforehand, it frees
  // them all.
  exr.num_channels = header.num_channels;
  if (LoadEXRImageFromMemory(&exr, &header, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) {
    image_owner.release();
    return fail("corrupt EXR");
  }
  if (exr.width != w64 || exr.height != h64 || exr.num_channels != header.num_channels)
    return ImageError{path, "EXR decoded to a size other than its dataWindow"};
  Image img(exr.width, exr.height);
  if (header.tiled || exr.images == nullptr) return ImageError{path, "corrupt EXR"};  // refused above
  copy_exr_pixels(header, exr, idx, gray, img);
  copy_string_attributes(header, img);
  return img;
}

}  // namespace

std::variant<Image, ImageError> read_image(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return ImageError{path, "cannot open the file"};
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), {});
  if (bytes.size() < 8) return ImageError{path, "too short to be a PNG or EXR image"};
  if (bytes.size() > (std::size_t{1} << 31)) return ImageError{path, "file larger than 2 GiB"};
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a};
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  if (std::memcmp(bytes.data(), kPng, 8) == 0) return decode_png(bytes, path);
  if (std::memcmp(bytes.data(), kExr, 4) == 0) return decode_exr(bytes, path);
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
  if (img.attributes.size() > TINYEXR_MAX_CUSTOM_ATTRIBUTES)
    throw WriteError(path + ": more than " + std::to_string(TINYEXR_MAX_CUSTOM_ATTRIBUTES) + " attributes");
  std::vector<EXRAttribute> attributes(img.attributes.size());
  for (std::size_t a = 0; a < img.attributes.size(); ++a) {
    const auto& [name, value] = img.attributes[a];
    if (name.empty() || name.size() > 255 || value.size() > (std::size_t{1} << 20))
      throw WriteError(path + ": attribute '" + name + "': name must be 1-255 bytes and value at most 1 MiB");
    std::memset(&attributes[a], 0, sizeof(EXRAttribute));
    std::strncpy(attributes[a].name, name.c_str(), 255);
    std::strncpy(attributes[a].type, "string", 255);
    attributes[a].value = reinterpret_cast<unsigned char*>(const_cast<char*>(value.data()));
    attributes[a].size = int(value.size());
  }
  header.num_custom_attributes = int(attributes.size());
  header.custom_attributes = attributes.empty() ? nullptr : attributes.data();
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
