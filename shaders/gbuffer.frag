#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: normal + inward thickness (rgba16f) and albedo + material id (rgba8).
#include "shared/gbuffer_main.glsl"

void main() { write_gbuffer(); }
