// UV atlases for texture-space diffusion (issue 6, DESIGN.md §5): whether a mesh's uv0
// can hold an irradiance texture (check_uvs), and a generated chart atlas for meshes
// whose uv0 cannot (generate_atlas). The texture path blurs irradiance in UV space with
// the fit's Gaussians, so the UVs must be injective (no two triangles on one texel),
// inside [0,1]^2, and not collapse any triangle.
//
// The generated atlas is a box projection (written here; no CGAL), in four steps:
//   1. each face takes the closest of the 6 ±axis directions to its normal, so the angle
//      θ between the normal and its axis has cos θ ≥ 1/√3;
//   2. charts grow breadth-first over edge-adjacent faces of one axis; a face whose
//      projection would overlap the chart's (separating-axis test, shared edges ignored)
//      is left for a later chart, so no chart folds over itself;
//   3. each chart is projected orthographically onto its axis plane and turned (one of
//      32 angles) to its smallest bounding box: projection and rotation keep every length
//      along the intersection of the face and the plane and shorten the steepest one by
//      cos θ, so UV length per mm lies in [s·cos θ, s] ⊂ [s/√3, s];
//   4. all charts share ONE scale s (UV units per scene unit), the largest for which a
//      shelf packing (first-fit decreasing height: Coffman, Garey, Johnson & Tarjan 1980,
//      "Performance bounds for level-oriented two-dimensional packing algorithms") fits
//      [0,1]^2 with `padding_texels` of empty texels around every chart at `resolution`
//      (room for the seam dilation of d'Eon & Luebke 2007).
//   5. seam gutters: for each chart, the triangles of other charts within reach of its
//      border (edge-adjacent, breadth-first, up to 1.5 x the padding's width in scene units
//      along the surface), unfolded across shared edges (each keeps the shared edge's UVs,
//      turns its third corner about that edge into the placed neighbour's plane and maps
//      it by the neighbour's own affine 3D -> UV map, so the chart's anisotropic scale
//      carries on), so the surface continues however sharply it turns at the border;
//      drawn behind the charts' own triangles, they fill the padding with the surface's
//      real continuation instead of an extrapolation (Mesh::uv_atlas_gutter).
// Before step 2, vertices are welded by position (to 1e-6 of the diagonal) and a face
// whose neighbours mostly took another axis within 54.7° of its normal takes it too.
#pragma once

#include "scene/Mesh.h"
#include "profiles/Profile.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sss::scene {

struct Scene;

struct UvCheckOptions {
  // A triangle is degenerate in UV when its UV area is below this fraction of what the
  // mesh's mean density (total UV area / total 3D area) gives its 3D area, or when its UV
  // area is below 1e-12 (a collapsed triangle). Triangles with (near) zero 3D area
  // (below 1e-12 of the squared bounding-box diagonal) cover no surface and are skipped.
  double min_relative_area = 1e-3;
  // Two triangles overlap when they still overlap by more than this (UV units) along
  // every one of their 6 edge normals (separating-axis test). Triangles sharing an edge
  // or a vertex touch with depth 0, so they never count; 1e-5 is 0.02 texel at 2048^2.
  double overlap_tolerance = 1e-5;
  // A vertex is outside [0,1]^2 when a coordinate is below -eps or above 1 + eps.
  double outside_tolerance = 1e-6;
};

struct UvCheck {
  bool usable = false;
  std::string reason;              // "" when usable; else readable, e.g. "12 triangles overlap in UV"
  std::size_t outside = 0;         // triangles with a vertex outside [0,1]^2 (or non-finite)
  std::size_t degenerate = 0;      // triangles collapsed in UV (see UvCheckOptions)
  std::size_t overlapping = 0;     // triangles overlapping another one
  bool overlap_count_is_lower_bound = false;  // the pair-test budget ran out (pathological UVs)
};

// Is mesh.uv0 usable for texture-space diffusion? (uv_atlas is not looked at.)
UvCheck check_uvs(const Mesh& mesh, const UvCheckOptions& options = {});
// The same checks on any UV set with one entry per position.
UvCheck check_uvs(const Mesh& mesh, const std::vector<glm::vec2>& uv,
                  const UvCheckOptions& options = {});

struct AtlasOptions {
  std::uint32_t resolution = 1024;    // texels per side the padding is measured at
  std::uint32_t padding_texels = 4;   // empty texels around each chart (>= 2 between charts)
  // How far (scene units, along the surface) a seam gutter may continue past its chart;
  // 0: as far as the padding holds (3 paddings). ensure_sss_atlases sets it from the
  // material's reach: where charts are packed small (many charts, s tiny) 3 paddings span
  // the whole mesh, and every chart's gutter would copy every other triangle.
  double max_gutter_reach = 0.0;
};

// What texture space generates with (GpuScene::ensure_sss_uvs): at least 12 texels of
// padding at 1024², more for a wide kernel (ensure_sss_atlases), leave room for the seam
// gutters a kernel reaches into.
inline constexpr AtlasOptions kLoadAtlasOptions{1024, 12};

struct AtlasChart {
  int axis = 0;                       // 0..5: +x, -x, +y, -y, +z, -z
  std::size_t triangles = 0;
  double area = 0.0;                  // 3D area, scene units^2
  glm::vec2 uv_min{0.0f}, uv_max{0.0f};  // the chart's box in the atlas (without padding)
};

struct AtlasStats {
  std::size_t charts = 0;
  double uv_per_unit = 0.0;           // s: UV units per scene unit, the same for every chart
  double utilization = 0.0;           // UV area covered by triangles / area of [0,1]^2
  double max_stretch = 0.0;           // max over triangles of (mm per UV) / (mm per UV at s): in [1, √3]
  std::size_t split_vertices = 0;     // vertices added by chart seams
  double seconds = 0.0;               // wall time of generate_atlas
};

// A seam gutter triangle: a triangle of another chart (within reach of the host chart's
// border across the surface) mapped by the host chart's own projection.
struct GutterTriangle {
  std::array<std::uint32_t, 3> source{};  // vertices of the input mesh
  std::array<glm::vec2, 3> uv{};
  std::array<float, 3> depth{};           // 0.25 .. 0.75: 0.25 + 0.5 distance / reach
  std::uint32_t host_triangle = 0;        // a triangle of the host chart
};

struct UvAtlas {
  std::vector<std::uint32_t> source_vertex;  // new vertex -> vertex of the input mesh
  std::vector<std::uint32_t> indices;        // the triangles (same order) on the new vertices
  std::vector<glm::vec2> uv;                 // one per new vertex, in [0,1]^2
  std::vector<std::uint32_t> triangle_chart; // one per triangle
  std::vector<AtlasChart> charts;
  std::vector<GutterTriangle> gutter;
  AtlasStats stats;
};

// Builds an atlas for `mesh` (its uv0 is ignored). Pure: the mesh is not changed.
UvAtlas build_atlas(const Mesh& mesh, const AtlasOptions& options = {});

// Builds an atlas and applies it: vertices on chart seams are duplicated (positions,
// normals, uv0 and tangents copied), the indices renumbered (triangle order kept), and
// the atlas written to mesh.uv_atlas (uv0 is kept: material textures still read it).
AtlasStats generate_atlas(Mesh& mesh, const AtlasOptions& options = {});

// The UVs the texture-space path reads: uv_atlas when generated, else uv0.
const std::vector<glm::vec2>& sss_uvs(const Mesh& mesh);

// UV islands: the connected pieces of a UV layout, as a dense id per vertex (0..count-1 in
// order of first appearance). Two vertices are on one island when a triangle joins them
// or when their UVs are equal (to 2^-20: split normals share a UV point); vertices no
// triangle uses get id 0 and count for no island. The texture path keeps its blur on one island.
struct UvIslands {
  std::vector<std::uint32_t> vertex_island;
  std::uint32_t count = 0;
};
UvIslands uv_islands(const std::vector<glm::vec2>& uv, const std::vector<std::uint32_t>& indices);

// The radius (mm) within which a profile keeps `fraction` of its total reflectance
// ∫ R(r) 2πr dr, the largest over the channels (a midpoint rule in ln r from 1e-4 mm out
// to 1e4 mm or the profile's support, 2% steps).
double reflectance_reach_mm(const profiles::RgbProfile& profile, double fraction);

// The share of a material's reflectance whose taps the seam gutter must hold: past the
// gutter a tap takes the point reflection about the centre (sss_texture.comp), exact only
// where the irradiance is linear; with 12 texels a small chart near the key's shadow edge
// kept its own light as a lighter triangular patch (issue 20 part 3).
inline constexpr double kGutterReflectanceShare = 0.9;
// How far past a chart's border its gutter continues the surface, in paddings: build_atlas
// unfolds gutter triangles out to 1.5 x the gap between two charts (3 paddings), but a
// chart owns only its own padding; the next padding out is its neighbour's, where the
// nearer gutter wins. So the continuation is 1 padding where two charts face each other
// and 2 where none does. ensure_sss_atlases sizes the padding with 1.5, between the two
// (a guarantee everywhere would take 1).
inline constexpr double kGutterReachInPaddings = 1.5;
// The most padding a reach may ask for at 1024²: the padding is paid around each of the
// charts, and the bunny's 74 keep 34% of the texture at 12 texels, 18% at 28, 13% at 32,
// 2% at 48 (mm per texel grows as the square root of that). At 28 the patches are gone
// from the frame; tests/scene/test_uv_atlas.cpp prints the gutter's reach in mm and the
// share of skin1's reflectance within it, at 1 and at 1.5 paddings, for 12 and 28 texels.
inline constexpr std::uint32_t kMaxPaddingTexels = 28;
// The gutter's reach along the surface, in reflectance reaches (AtlasOptions::
// max_gutter_reach): a blur tap never lands further from a chart's border than the kernel
// reaches, and 2 x the radius holding 90% holds 99.99% of a Gaussian (r90 = 2.15σ) and
// more than 99% of the dipole-like profiles' exponential tails.
inline constexpr double kGutterReachInReaches = 2.0;

// For every mesh drawn with a subsurface material whose uv0 fails check_uvs and that has
// no uv_atlas yet: generate_atlas() and a note in Scene::texture_notes, "mesh NAME:
// generated a UV atlas (REASON)". The padding is options.padding_texels, or more when the
// material's profile needs it: enough (up to kMaxPaddingTexels, scaled with the
// resolution) that kGutterReachInPaddings paddings reach the radius holding
// kGutterReflectanceShare of its reflectance (reflectance_reach_mm).
// Returns how many atlases were generated. Not called on load: the renderer calls it in
// texture mode (GpuScene::ensure_sss_uvs; README: "UV atlas").
std::size_t ensure_sss_atlases(Scene& scene, const AtlasOptions& options = {});

}  // namespace sss::scene
