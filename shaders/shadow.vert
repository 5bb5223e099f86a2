#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow map: depth from the light (layer = light index).
#include "shared/frame.h"

layout(set = 0, binding = 0) uniform Lights { LightBlock light_block; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_position;

void main() {
  int light = int(draw.material.y);
  gl_Position = light_block.lights[light].shadow_matrix * (draw.model * vec4(in_position, 1.0));
}
