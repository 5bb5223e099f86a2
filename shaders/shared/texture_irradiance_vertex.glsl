// Texture path, irradiance raster: each triangle of one object drawn at its atlas UVs
// (texel (x, y) of an N x N target is UV ((x + 0.5) / N, (y + 0.5) / N)), carrying its
// world position, normal, material UVs and UV island to texture_irradiance.frag; the
// mesh's seam gutter (Mesh::uv_atlas_gutter) is drawn with it, behind.
#include "mesh_vertex.glsl"

layout(location = 4) flat out float out_island;

void main() {
  write_surface_outputs();
  out_island = in_atlas.z;
  // z: 0 for the mesh's own triangles, 0.25..0.75 for its seam gutter (GpuVertex::atlas),
  // so that with a LESS depth test its own texels are never overwritten by a gutter.
  gl_Position = vec4(in_atlas.xy * 2.0 - 1.0, in_atlas.w, 1.0);
}
