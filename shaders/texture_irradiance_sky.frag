#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, atlas G-buffer with an environment: also the sky's blocked irradiance
// (shared/texture_irradiance_fragment.glsl).
#define SSS_SKY_OCCLUSION 1
#include "shared/texture_irradiance_fragment.glsl"
