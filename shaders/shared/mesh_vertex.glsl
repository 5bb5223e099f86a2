// The vertex stage of the passes that draw the scene's meshes with every attribute
// (gbuffer.vert, texture_irradiance.vert and their _sky variants): the GpuVertex inputs, the surface outputs
// surface.glsl reads, and their transform by the draw's model matrix. Not shared with C++.
#ifndef SSS_SHADERS_MESH_VERTEX_GLSL
#define SSS_SHADERS_MESH_VERTEX_GLSL

#include "frame.h"

layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 4) in vec4 in_atlas;  // u, v, UV island, atlas raster depth
layout(location = 5) in float in_thickness;  // along -n out of the mesh, mesh units; -1: none
layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;
// The inward thickness in world units, interpolated (a flat value would show the facets in
// the transmitted light). A vertex without one gets 1e20: no transmission, and a triangle
// that reaches it fades to none.
layout(location = 5) out float out_thickness;
#ifdef SSS_SKY_OCCLUSION
// The sky's blocked transfer (reference/SkyOcclusion.h), 9 coefficients from binding 1
// (GpuScene: per instance), interpolated like the thickness.
layout(location = 6) in vec3 in_sky[3];
layout(location = 6) out vec3 out_sky[3];
#endif

// Writes outputs 0..3 and 5 (world position, normal, material UV, tangent, inward
// thickness), and 6..8 (the sky's blocked transfer) with SSS_SKY_OCCLUSION; returns the
// world position.
vec4 write_surface_outputs() {
  vec4 world = draw.model * vec4(in_position, 1.0);
  out_world = world.xyz;
  out_normal = transpose(inverse(mat3(draw.model))) * in_normal;
  out_uv = in_uv;
  out_tangent = vec4(mat3(draw.model) * in_tangent.xyz, in_tangent.w);
  // The segment from the vertex to its exit maps to world space as a whole (an affine
  // model keeps it on the line, ending on the same surface point): its world length is
  // |M n| d for the unit local normal n.
  out_thickness = in_thickness < 0.0 ? 1e20 : length(mat3(draw.model) * normalize(in_normal)) * in_thickness;
#ifdef SSS_SKY_OCCLUSION
  out_sky = in_sky;
#endif
  return world;
}

#endif
