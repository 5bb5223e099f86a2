#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, irradiance raster (shared/texture_irradiance_vertex.glsl).
#include "shared/texture_irradiance_vertex.glsl"
