// What the tools' --no-specular output must be against the whole frame of the same render
// (sss-viewer and sss-reference tests): the same alpha everywhere, and every colour value
// at most the whole frame's (the specular taken off is >= 0). The bound allows the
// float rounding of a - b: 1e-6 relative (8 ulp of a float) plus 1e-7 absolute for
// values near 0. Returns what a test asserts next: the largest drop (a highlight was
// taken off) and how many colour values are unchanged (where there was no specular).
#pragma once

#include "image/Image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>

namespace sss::testing {

struct HighlightTakenOff {
  double largest_drop = 0.0;
  std::size_t unchanged = 0;
};

inline HighlightTakenOff check_frame_less_highlight(const image::Image& whole, const image::Image& less) {
  HighlightTakenOff h;
  EXPECT_EQ(whole.rgba.size(), less.rgba.size());
  if (whole.rgba.size() != less.rgba.size()) return h;
  for (std::size_t i = 0; i < whole.rgba.size(); ++i) {
    if (i % 4 == 3) {
      EXPECT_EQ(whole.rgba[i], less.rgba[i]) << "alpha at pixel " << i / 4;
      continue;
    }
    EXPECT_LE(less.rgba[i], whole.rgba[i] * (1.0f + 1e-6f) + 1e-7f) << "value " << i;
    h.largest_drop = std::max(h.largest_drop, double(whole.rgba[i] - less.rgba[i]));
    if (whole.rgba[i] == less.rgba[i]) ++h.unchanged;
  }
  return h;
}

}  // namespace sss::testing
