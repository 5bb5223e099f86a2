// The display transform of the real-time composite (shaders/composite.comp), on the CPU,
// so that the reference renderer's PNG is comparable with the GPU's code for code:
// exposure, Narkowicz's fit of the ACES filmic curve (Narkowicz 2015, "ACES Filmic Tone
// Mapping Curve"), sRGB encoding (IEC 61966-2-1). Alpha is kept.
#pragma once

#include "image/Image.h"

namespace sss::image {

float filmic(float x);  // [0, ∞) -> [0, 1]

// Linear HDR radiance -> display values (sRGB codes / 255), alpha copied.
Image tonemap(const Image& hdr, float exposure = 1.0f);

}  // namespace sss::image
