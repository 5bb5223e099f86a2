// The display transform's formulas, stated once for the GPU composite (composite.glsl)
// and the CPU (image: Tonemap.cpp's filmic, Image.cpp's sRGB encode and decode),
// so that the reference's PNG and the real-time frame's display image are the same
// function of radiance. Included by both languages: the preprocessor subset only, and
// literals through SSS_F (float in C++, GLSL's default float in GLSL).
//   Narkowicz 2015, "ACES Filmic Tone Mapping Curve": f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)
//   sRGB (IEC 61966-2-1): encode 12.92 c below 0.0031308, else 1.055 c^(1/2.4) − 0.055;
//   decode c / 12.92 below 0.04045, else ((c + 0.055) / 1.055)^2.4
// C++:  #include "shaders/shared/tonemap.h"      GLSL:  #include "shared/tonemap.h"
#ifndef SSS_SHADERS_SHARED_TONEMAP_H
#define SSS_SHADERS_SHARED_TONEMAP_H

#ifdef __cplusplus
#define SSS_F(x) x##f
#else
#define SSS_F(x) x
#endif

// The filmic curve before its clamp to [0, 1]; x is evaluated several times.
#define SSS_FILMIC_CURVE(x) \
  (((x) * (SSS_F(2.51) * (x) + SSS_F(0.03))) / ((x) * (SSS_F(2.43) * (x) + SSS_F(0.59)) + SSS_F(0.14)))

#define SSS_SRGB_ENCODE_CUTOFF SSS_F(0.0031308)
#define SSS_SRGB_DECODE_CUTOFF SSS_F(0.04045)
#define SSS_SRGB_LINEAR_SLOPE SSS_F(12.92)
#define SSS_SRGB_SCALE SSS_F(1.055)
#define SSS_SRGB_OFFSET SSS_F(0.055)
#define SSS_SRGB_GAMMA SSS_F(2.4)

#endif  // SSS_SHADERS_SHARED_TONEMAP_H
