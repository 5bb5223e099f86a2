#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, the final lookup: each pixel of an object with an irradiance atlas reads
// its scattered irradiance Σ w_i (E * G_i) from the atlas at the pixel's atlas UV
// (bilinear), into the frame's accum target, where the composite reads it as it reads the
// gaussians mode's. Drawn with gbuffer.vert and a depth test against the G-buffer's
// depth, so only the visible surface writes. Alpha 1 marks the pixels it wrote.
#include "shared/frame.h"

layout(set = 0, binding = 1) uniform sampler2D scattered[SSS_MAX_TEXTURE_OBJECTS];
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 4) in vec4 in_atlas;
layout(location = 0) out vec4 out_scattered;

void main() {
  out_scattered = vec4(texture(scattered[int(draw.material.w)], in_atlas.xy).rgb, 1.0);
}
