// The node hierarchy of the default scene, flattened: instances, cameras and lights in
// world space. The graph is checked first (indices, one parent per node, no cycles), and
// it is walked with an explicit stack, so no file can make it recurse deeply.
#include "scene/GltfContext.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <limits>

namespace sss::scene {

namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();

Status finite_vector(GltfContext& ctx, const std::string& object, const char* field,
                     const std::vector<double>& v, std::size_t size) {
  if (v.empty()) return std::nullopt;
  if (v.size() != size)
    return ctx.fail(object, field, "must have " + std::to_string(size) + " numbers, got " +
                                       std::to_string(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]) || std::fabs(v[i]) > kFloatMax)
      return ctx.fail(object, std::string(field) + "[" + std::to_string(i) + "]",
                      "must be a finite number that fits a float, got " + number_text(v[i]));
  return std::nullopt;
}

Status local_matrix(GltfContext& ctx, std::size_t i, glm::dmat4& out) {
  const tinygltf::Node& n = ctx.model.nodes[i];
  const std::string object = indexed("nodes", i);
  if (auto e = finite_vector(ctx, object, "matrix", n.matrix, 16)) return e;
  if (auto e = finite_vector(ctx, object, "translation", n.translation, 3)) return e;
  if (auto e = finite_vector(ctx, object, "rotation", n.rotation, 4)) return e;
  if (auto e = finite_vector(ctx, object, "scale", n.scale, 3)) return e;
  if (!n.matrix.empty()) {
    if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
      return ctx.fail(object, "matrix", "cannot be combined with translation, rotation or scale");
    out = glm::make_mat4(n.matrix.data());  // column-major, like glTF
    return std::nullopt;
  }
  glm::dmat4 m(1.0);
  if (!n.translation.empty())
    m[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  if (!n.rotation.empty()) {
    glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // glTF: x y z w
    const double len = glm::length(q);
    if (!(len > 1e-12)) return ctx.fail(object, "rotation", "is a zero quaternion");
    if (std::fabs(len - 1.0) > 1e-3)
      ctx.scene.warnings.push_back(ctx.file + ": " + object + ".rotation: not a unit quaternion "
                                   "(length " + number_text(len) + "); normalised");
    m = m * glm::mat4_cast(q / len);
  }
  if (!n.scale.empty()) m = m * glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  out = m;
  return std::nullopt;
}

}  // namespace

namespace {

// One parent per node: parent[c] is the node that lists c as a child, -1 for none.
Status find_parents(GltfContext& ctx, std::vector<long long>& parent) {
  const auto& nodes = ctx.model.nodes;
  parent.assign(nodes.size(), -1);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (std::size_t k = 0; k < nodes[i].children.size(); ++k) {
      const int c = nodes[i].children[k];
      const std::string field = "children[" + std::to_string(k) + "]";
      if (auto e = out_of_range("nodes", c, nodes.size())) return ctx.fail(indexed("nodes", i), field, *e);
      if (std::size_t(c) == i) return ctx.fail(indexed("nodes", i), field, "is the node itself (a cycle)");
      if (parent[std::size_t(c)] >= 0)
        return ctx.fail(indexed("nodes", i), field,
                        "nodes[" + std::to_string(c) + "] is already a child of nodes[" +
                            std::to_string(parent[std::size_t(c)]) + "]; a node may have only one parent");
      parent[std::size_t(c)] = static_cast<long long>(i);
    }
  }
  return std::nullopt;
}

// No cycles: follow each parent chain once (0 unseen, 1 on the current chain, 2 done).
Status check_no_cycles(GltfContext& ctx, const std::vector<long long>& parent) {
  const auto& nodes = ctx.model.nodes;
  std::vector<unsigned char> state(nodes.size(), 0);
  std::vector<std::size_t> chain;
  for (std::size_t start = 0; start < nodes.size(); ++start) {
    chain.clear();
    long long x = static_cast<long long>(start);
    while (x >= 0 && state[std::size_t(x)] == 0) {
      state[std::size_t(x)] = 1;
      chain.push_back(std::size_t(x));
      x = parent[std::size_t(x)];
    }
    if (x >= 0 && state[std::size_t(x)] == 1)
      return ctx.fail(indexed("nodes", std::size_t(x)), "children", "the node is its own ancestor (a cycle)");
    for (std::size_t c : chain) state[c] = 2;
  }
  return std::nullopt;
}

// The roots of the default scene (every parentless node, with a warning, when the file has
// no scenes), each listed once and none a child.
Status scene_roots(GltfContext& ctx, const std::vector<long long>& parent, std::vector<std::size_t>& roots) {
  const auto& nodes = ctx.model.nodes;
  if (ctx.model.scenes.empty()) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (parent[i] < 0) roots.push_back(i);
    if (!roots.empty())
      ctx.scene.warnings.push_back(ctx.file + ": no scenes; showing every root node");
  } else {
    const int s = ctx.model.defaultScene >= 0 ? ctx.model.defaultScene : 0;
    if (auto e = out_of_range("scenes", s, ctx.model.scenes.size())) return ctx.fail("", "scene", *e);
    const auto& list = ctx.model.scenes[std::size_t(s)].nodes;
    std::vector<bool> listed(nodes.size(), false);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const std::string object = indexed("scenes", std::size_t(s)), field = "nodes[" + std::to_string(k) + "]";
      if (auto e = out_of_range("nodes", list[k], nodes.size())) return ctx.fail(object, field, *e);
      const std::size_t r = std::size_t(list[k]);
      if (listed[r]) return ctx.fail(object, field, "nodes[" + std::to_string(r) + "] is listed twice");
      if (parent[r] >= 0)
        return ctx.fail(object, field, "nodes[" + std::to_string(r) + "] is a child of nodes[" +
                                           std::to_string(parent[r]) + "], not a root");
      listed[r] = true;
      roots.push_back(r);
    }
  }
  return std::nullopt;
}

// Node i, at `world`: its instances, camera and light; a skin is warned about once.
Status add_node(GltfContext& ctx, std::size_t i, const glm::dmat4& world, bool& warned_skin) {
  const tinygltf::Node& n = ctx.model.nodes[i];
  const std::string object = indexed("nodes", i);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!(std::fabs(world[c][r]) <= kFloatMax))
        return ctx.fail(object, "", "its world transform is not finite in float precision");
  if (n.mesh >= 0) {
    if (auto e = out_of_range("meshes", n.mesh, ctx.model.meshes.size())) return ctx.fail(object, "mesh", *e);
    // Instances multiply: many nodes may each show a mesh of many primitives.
    const auto& prims = ctx.mesh_primitives[std::size_t(n.mesh)];
    if (auto e = ctx.charge(prims.size() * (sizeof(Instance) + n.name.size()), object)) return e;
    for (std::uint32_t m : prims)
      ctx.scene.instances.push_back({m, glm::mat4(world), n.name.empty() ? object : n.name});
  } else if (n.mesh < -1) {
    return ctx.fail(object, "mesh", "must be a mesh index, got " + std::to_string(n.mesh));
  }
  if (n.skin >= 0 && !warned_skin) {
    ctx.scene.warnings.push_back(ctx.file + ": skins are not supported; meshes shown in bind pose");
    warned_skin = true;
  }
  if (n.camera >= 0 || n.camera < -1)
    if (auto e = add_camera(ctx, n.camera, world, object)) return e;
  if (const auto ext = n.extensions.find("KHR_lights_punctual"); ext != n.extensions.end())
    if (auto e = add_light(ctx, ext->second, world, object)) return e;
  return std::nullopt;
}

}  // namespace

Status convert_nodes(GltfContext& ctx) {
  const auto& nodes = ctx.model.nodes;
  if (nodes.size() > ctx.options.max_nodes)
    return ctx.fail("nodes", "", std::to_string(nodes.size()) + " nodes, more than the limit of " +
                                     std::to_string(ctx.options.max_nodes));
  std::vector<long long> parent;
  if (auto e = find_parents(ctx, parent)) return e;
  if (auto e = check_no_cycles(ctx, parent)) return e;
  std::vector<std::size_t> roots;
  if (auto e = scene_roots(ctx, parent, roots)) return e;
  // Walk down from the roots.
  bool warned_skin = false;
  std::vector<std::pair<std::size_t, glm::dmat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
  while (!stack.empty()) {
    const auto [i, parent_world] = stack.back();
    stack.pop_back();
    glm::dmat4 local;
    if (auto e = local_matrix(ctx, i, local)) return e;
    const glm::dmat4 world = parent_world * local;
    if (auto e = add_node(ctx, i, world, warned_skin)) return e;
    for (auto c = nodes[i].children.rbegin(); c != nodes[i].children.rend(); ++c)
      stack.emplace_back(std::size_t(*c), world);
  }
  return std::nullopt;
}

}  // namespace sss::scene
