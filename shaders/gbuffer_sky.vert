#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer vertex stage with an environment: also the sky's blocked transfer (binding 1).
#define SSS_SKY_OCCLUSION 1
#include "shared/gbuffer_vertex.glsl"
