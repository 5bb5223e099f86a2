#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, irradiance raster with an environment: also the sky's blocked transfer
// (shared/texture_irradiance_vertex.glsl).
#define SSS_SKY_OCCLUSION 1
#include "shared/texture_irradiance_vertex.glsl"
