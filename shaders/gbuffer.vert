#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: world position and normal of each vertex, and the texture path's atlas
// coordinates (texture_gather.frag draws with this shader too, so that its depth test
// against the G-buffer finds the G-buffer's own fragments: the same code on the same
// inputs gives the same depth. Not declared `invariant`: Mesa 22.3 warns about the
// decoration glslang puts on the gl_PerVertex member).
#include "shared/frame.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_atlas;
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;
layout(location = 4) out vec4 out_atlas;

void main() {
  vec4 world = draw.model * vec4(in_position, 1.0);
  out_world = world.xyz;
  out_normal = transpose(inverse(mat3(draw.model))) * in_normal;
  out_uv = in_uv;
  out_tangent = vec4(mat3(draw.model) * in_tangent.xyz, in_tangent.w);
  out_atlas = in_atlas;
  gl_Position = frame.view_proj * world;
}
