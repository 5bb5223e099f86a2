// sss_fuzz_image: a PNG or EXR file as sss-compare reads it (FuzzTargets.h).
#include "FuzzSupport.h"
#include "FuzzTargets.h"

#include "image/Image.h"

#include <cmath>
#include <cstring>

int sss_fuzz_image(const std::uint8_t* data, std::size_t size) {
  // read_image chooses by magic, whatever the name; the name follows the magic too
  // (EXR: 76 2f 31 01, OpenEXR file layout §"Magic number").
  static constexpr std::uint8_t kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
  const bool exr = size >= 4 && std::memcmp(data, kExrMagic, 4) == 0;
  const std::string name = exr ? "input.exr" : "input.png";
  const std::string path = sss::fuzz::write_scratch(name, data, size);
  auto read = sss::image::read_image(path);
  sss::fuzz::remove_scratch(name);
  if (auto* img = std::get_if<sss::image::Image>(&read)) {
    sss::fuzz::fuzz_check(img->width > 0 && img->height > 0 &&
                              img->width <= sss::image::kMaxImageSide &&
                              img->height <= sss::image::kMaxImageSide,
                          "an accepted image has a size in 1..kMaxImageSide");
    sss::fuzz::fuzz_check(img->rgba.size() == std::size_t(img->width) * std::size_t(img->height) * 4,
                          "rgba holds width * height * 4 floats");
    sss::fuzz::count_accepted();
  }
  return 0;
}
