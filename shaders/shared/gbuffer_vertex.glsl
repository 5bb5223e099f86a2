// The G-buffer's vertex stage (gbuffer.vert, gbuffer_sky.vert): world position and normal
// of each vertex, and the texture path's atlas coordinates (texture_gather.frag draws with
// gbuffer.vert, so that its depth test against the G-buffer finds the G-buffer's own
// fragments: the same code on the same inputs gives the same depth; with an environment
// the G-buffer draws with gbuffer_sky.vert, whose position is the same code, and the
// lookup's depth bias (TextureGatherPass.cpp) covers any difference in rounding. Not
// declared `invariant`: Mesa 22.3 warns about the decoration glslang puts on the
// gl_PerVertex member).
#include "mesh_vertex.glsl"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(location = 4) out vec4 out_atlas;

void main() {
  vec4 world = write_surface_outputs();
  out_atlas = in_atlas;
  gl_Position = frame.view_proj * world;
}
