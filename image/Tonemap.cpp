#include "image/Tonemap.h"

#include "shaders/shared/tonemap.h"

#include <algorithm>
#include <cmath>

namespace sss::image {

float filmic(float x) {
  x = std::max(x, 0.0f);
  return std::clamp(SSS_FILMIC_CURVE(x), 0.0f, 1.0f);
}

Image tonemap(const Image& hdr, float exposure) {
  Image out(hdr.width, hdr.height);
  for (int y = 0; y < hdr.height; ++y)
    for (int x = 0; x < hdr.width; ++x) {
      const float* in = hdr.pixel(x, y);
      float* o = out.pixel(x, y);
      for (int c = 0; c < 3; ++c) o[c] = srgb_encode(filmic(in[c] * exposure));
      o[3] = in[3];
    }
  return out;
}

}  // namespace sss::image
