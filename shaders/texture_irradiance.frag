#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, atlas G-buffer (shared/texture_irradiance_fragment.glsl).
#include "shared/texture_irradiance_fragment.glsl"
