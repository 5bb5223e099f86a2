// Shapes: meshes built in code for the built-in scenes. CCW winding seen from outside,
// unit normals, uv0 and tangents (w = +1), sizes in scene units.
#pragma once

#include "scene/Mesh.h"

#include <cstdint>

namespace sss::scene {

// A UV sphere around the origin: `segments` around the equator, `rings` pole to pole;
// u runs with longitude, v from the north pole (v = 0) to the south pole.
Mesh make_uv_sphere(float radius, std::uint32_t segments = 64, std::uint32_t rings = 32,
                    std::uint32_t material = 0);

// An axis-aligned box with flat faces (4 vertices each, uv 0..1 per face).
Mesh make_box(const glm::vec3& min, const glm::vec3& max, std::uint32_t material = 0);

}  // namespace sss::scene
