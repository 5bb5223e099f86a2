#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer with an environment: gbuffer.frag's targets plus, in a third, the irradiance
// of the sky that the scene blocks (shared/surface.glsl, sky_blocked).
#define SSS_SKY_OCCLUSION 1
#include "shared/gbuffer_main.glsl"

void main() { write_gbuffer(); }
