// Constants shared by the C++ renderer and the GLSL shaders (included by both; keep it
// to the preprocessor subset both languages understand). C++ type aliases are guarded
// by __cplusplus; GLSL sees the macros only.
//
// C++:  #include "shaders/shared/config.h"      GLSL:  #include "shared/config.h"
#ifndef SSS_SHADERS_SHARED_CONFIG_H
#define SSS_SHADERS_SHARED_CONFIG_H

// The most Gaussians in one fitted profile. Must equal sss::profiles::kMaxGaussians
// (tests/vk/ShaderConfigTest.cpp checks it at compile time).
#define SSS_MAX_GAUSSIANS 8

// The SSS technique (renderer::SssTechnique; FrameUniforms::options.y).
#define SSS_TECHNIQUE_OFF 0
#define SSS_TECHNIQUE_SEPARABLE 1
#define SSS_TECHNIQUE_GAUSSIANS 2
#define SSS_TECHNIQUE_TEXTURE 3

// Compute workgroup sizes. 8x8 suits image passes (subgroup size 8 on lavapipe, 32-64 on
// GPUs); 64 suits 1D passes over buffers.
#define SSS_WORKGROUP_2D_X 8
#define SSS_WORKGROUP_2D_Y 8
#define SSS_WORKGROUP_1D 64

#ifdef __cplusplus
#include <cstdint>
namespace sss::shader {
// GLSL scalar names, so that structs in shaders/shared/*.h read the same in both.
using uint = std::uint32_t;
inline constexpr uint kMaxGaussians = SSS_MAX_GAUSSIANS;
inline constexpr uint kWorkgroup2DX = SSS_WORKGROUP_2D_X;
inline constexpr uint kWorkgroup2DY = SSS_WORKGROUP_2D_Y;
inline constexpr uint kWorkgroup1D = SSS_WORKGROUP_1D;
}  // namespace sss::shader
#endif

#endif  // SSS_SHADERS_SHARED_CONFIG_H
