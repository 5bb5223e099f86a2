#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer vertex stage (shared/gbuffer_vertex.glsl).
#include "shared/gbuffer_vertex.glsl"
