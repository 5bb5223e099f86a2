// Inward thickness of a mesh, per vertex: how far a ray from the vertex along its inward
// normal (-n) travels before it leaves the object, in the mesh's own units. The GPU's
// environment light uses it for the sky's transmission through thin parts (shading.glsl):
// a light's shadow map gives the thickness along that light, but the sky lights the far
// side from every direction, and what crosses to P is what enters the surface behind it,
// d away along -n (the "local thickness" that Barré-Brisebois & Bouchard 2011, GDC
// "Approximating Translucency for a Fast, Cheap and Convincing Subsurface Scattering
// Look", bake per vertex for the same purpose; they bake an ambient-occlusion estimate of
// it, this casts the one ray). Ray-cast with Embree (RayScene), so it lives here rather
// than in the Vulkan renderer that uploads it.
#pragma once

#include "scene/Mesh.h"

#include <vector>

namespace sss::reference {

// One value per mesh vertex: the distance along -normal to the first surface of the mesh
// beyond a start offset of 1e-4 x the mesh's bounding diagonal (which skips the vertex's
// own triangles), the ray starting a thousandth of the way toward the triangles around
// the vertex (Thickness.cpp says why); -1 where the ray leaves without a hit (an open
// mesh, a plane) or the normal is not usable. Empty when the mesh has no triangles. A box's
// face vertex gets the box's side; a sphere's vertex with a radial normal the diameter,
// within 1e-3 of an edge x the facets' tilt (tests/reference/test_thickness.cpp).
std::vector<float> inward_thickness(const scene::Mesh& mesh);

// Per vertex, the mean of the centroids of the triangles around it (the vertex itself when
// none is): where the per-vertex bakes (inward_thickness, sky_occlusion) nudge a ray's
// start a thousandth of the way, off the edges and creases the vertex lies on.
std::vector<glm::vec3> fan_centroids(const std::vector<glm::vec3>& positions,
                                     const std::vector<std::uint32_t>& indices);

}  // namespace sss::reference
