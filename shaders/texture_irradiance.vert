#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, irradiance raster: each triangle of one object drawn at its atlas UVs
// (texel (x, y) of an N x N target is UV ((x + 0.5) / N, (y + 0.5) / N)), carrying its
// world position, normal, material UVs and UV island to texture_irradiance.frag; the
// mesh's seam gutter (Mesh::uv_atlas_gutter) is drawn with it, behind.
#include "shared/frame.h"

layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_atlas;  // u, v, island, 1 when usable
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;
layout(location = 4) flat out float out_island;

void main() {
  out_world = (draw.model * vec4(in_position, 1.0)).xyz;
  out_normal = transpose(inverse(mat3(draw.model))) * in_normal;
  out_uv = in_uv;
  out_tangent = vec4(mat3(draw.model) * in_tangent.xyz, in_tangent.w);
  out_island = in_atlas.z;
  // z: 0 for the mesh's own triangles, 0.25..0.75 for its seam gutter (GpuVertex::atlas),
  // so that with a LESS depth test its own texels are never overwritten by a gutter.
  gl_Position = vec4(in_atlas.xy * 2.0 - 1.0, in_atlas.w, 1.0);
}
