// Accessors and buffer views: every index, byte range, stride and alignment is checked
// with overflow-safe 64-bit arithmetic before a byte is read (glTF 2.0 §3.6).
#include "scene/GltfContext.h"

#include <cmath>
#include <cstring>

namespace sss::scene {

namespace {

int component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // DOUBLE and anything else are not glTF 2.0 component types
  }
}

const char* component_name(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    default: return "an invalid component type";
  }
}

int type_components(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;  // matrices: never a vertex attribute we read
  }
}

struct Located {
  const unsigned char* data = nullptr;  // first element
  std::uint64_t stride = 0;
  std::uint64_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

// Checks accessors[index] for use as `components` components and finds its bytes.
Status locate(GltfContext& ctx, int index, int components, const std::string& object,
              const std::string& field, Located& out) {
  const auto& accessors = ctx.model.accessors;
  if (auto e = out_of_range("accessors", index, accessors.size()))
    return ctx.fail(object, field, *e);
  const tinygltf::Accessor& a = accessors[std::size_t(index)];
  const std::string name = indexed("accessors", std::size_t(index));
  if (a.sparse.isSparse) return ctx.fail(name, "sparse", "sparse accessors are not supported");
  if (a.count == 0) return ctx.fail(name, "count", "must be >= 1");
  const int csize = component_size(a.componentType);
  if (csize == 0)
    return ctx.fail(name, "componentType", std::to_string(a.componentType) +
                                               " is not a glTF 2.0 component type");
  if (type_components(a.type) != components)
    return ctx.fail(name, "type", "must have " + std::to_string(components) +
                                      " component(s) for " + object + "." + field);
  if (a.bufferView < 0)
    return ctx.fail(name, "bufferView",
                    "is missing; accessors without a buffer view (all zeros) are not supported");
  if (auto e = out_of_range("bufferViews", a.bufferView, ctx.model.bufferViews.size()))
    return ctx.fail(name, "bufferView", *e);
  const tinygltf::BufferView& view = ctx.model.bufferViews[std::size_t(a.bufferView)];
  const std::string view_name = indexed("bufferViews", std::size_t(a.bufferView));
  const std::uint64_t element = std::uint64_t(csize) * std::uint64_t(components);
  const std::uint64_t stride = view.byteStride ? view.byteStride : element;
  if (stride < element)
    return ctx.fail(view_name, "byteStride", std::to_string(stride) + " is smaller than the " +
                                                 std::to_string(element) + "-byte elements of " + name);
  if (a.byteOffset >= view.byteLength)
    return ctx.fail(name, "byteOffset", std::to_string(a.byteOffset) + " lies past the " +
                                            std::to_string(view.byteLength) + " bytes of " + view_name);
  if (a.byteOffset % std::uint64_t(csize) != 0 ||
      (std::uint64_t(view.byteOffset) + a.byteOffset) % std::uint64_t(csize) != 0)
    return ctx.fail(name, "byteOffset", "is not aligned to its " + std::to_string(csize) +
                                            "-byte components (" + component_name(a.componentType) + ")");
  if (stride % std::uint64_t(csize) != 0)
    return ctx.fail(view_name, "byteStride", "is not a multiple of the component size of " + name);
  // offset + stride * (count - 1) + element <= view length, without overflow.
  std::uint64_t span = 0, end = 0;
  if (__builtin_mul_overflow(stride, std::uint64_t(a.count) - 1, &span) ||
      __builtin_add_overflow(span, element, &end) ||
      __builtin_add_overflow(end, std::uint64_t(a.byteOffset), &end) || end > view.byteLength)
    return ctx.fail(name, "count",
                    std::to_string(a.count) + " elements of " + std::to_string(element) +
                        " bytes, stride " + std::to_string(stride) + ", from byteOffset " +
                        std::to_string(a.byteOffset) + " run past the " +
                        std::to_string(view.byteLength) + " bytes of " + view_name);
  const auto& buffer = ctx.model.buffers[std::size_t(view.buffer)];  // checked by check_buffer_views
  out.data = buffer.data.data() + view.byteOffset + a.byteOffset;
  out.stride = stride;
  out.count = a.count;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  return std::nullopt;
}

template <typename T>
T load(const unsigned char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace

namespace {

// Whether the rule takes the accessor's component type (FLOAT; normalized 8/16-bit where
// the rule allows; signed and integer types only with KHR_mesh_quantization); if not, the
// message that says what it expects.
std::optional<std::string> component_type_refused(const AttributeRule& rule, const Located& at, bool q) {
  const int ct = at.component_type;
  const bool small_int = ct != TINYGLTF_COMPONENT_TYPE_FLOAT && ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  const bool signed_int = ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT;
  const bool ok = (ct == TINYGLTF_COMPONENT_TYPE_FLOAT && !at.normalized) ||
                  (rule.unorm8 && ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && at.normalized) ||
                  (rule.unorm16 && ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && at.normalized) ||
                  (q && rule.snorm && signed_int && at.normalized) || (q && rule.integers && small_int);
  if (ok) return std::nullopt;
  return std::string(rule.semantic) + " cannot be " + (at.normalized ? "normalized " : "") + component_name(ct) +
         "; expected FLOAT" + (rule.unorm8 ? ", normalized UNSIGNED_BYTE" : "") +
         (rule.unorm16 ? ", normalized UNSIGNED_SHORT" : "") + (q && rule.snorm ? ", normalized BYTE or SHORT" : "") +
         (q && rule.integers ? ", any 8- or 16-bit integer" : "") +
         (!q && (rule.snorm || rule.integers) && small_int
              ? " (quantized attributes need KHR_mesh_quantization in extensionsUsed)"
              : "");
}

// Component c of the element at p as a float. glTF 2.0 §3.11 (animation samplers'
// normalized integers, which KHR_mesh_quantization uses too): f = c / 255, c / 65535;
// max(c / 127, -1), max(c / 32767, -1). Unnormalized integers are their value.
float component_value(const unsigned char* p, int c, int ct, bool normalized) {
  switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p + 4 * c);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(p[c]) / 255.0f : float(p[c]);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float u = float(load<std::uint16_t>(p + 2 * c));
      return normalized ? u / 65535.0f : u;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float b = float(load<std::int8_t>(p + c));
      return normalized ? std::max(b / 127.0f, -1.0f) : b;
    }
    default: {  // SHORT
      const float h = float(load<std::int16_t>(p + 2 * c));
      return normalized ? std::max(h / 32767.0f, -1.0f) : h;
    }
  }
}

}  // namespace

Status read_attribute(GltfContext& ctx, int index, const AttributeRule& rule,
                      const std::string& object, const std::string& field,
                      std::vector<float>& out) {
  Located at;
  if (auto e = locate(ctx, index, rule.components, object, field, at)) return e;
  const std::string name = indexed("accessors", std::size_t(index));
  if (auto why = component_type_refused(rule, at, ctx.mesh_quantization))
    return ctx.fail(name, "componentType", *why);
  const std::uint64_t n = at.count * std::uint64_t(rule.components);
  if (auto e = ctx.charge(n * sizeof(float), name)) return e;
  out.resize(n);
  for (std::uint64_t i = 0; i < at.count; ++i) {
    const unsigned char* p = at.data + i * at.stride;
    for (int c = 0; c < rule.components; ++c) {
      const float v = component_value(p, c, at.component_type, at.normalized);
      if (!std::isfinite(v))
        return ctx.fail(object, field, name + " element " + std::to_string(i) + " component " +
                                           std::to_string(c) + " is " + number_text(v) +
                                           "; values must be finite");
      out[i * rule.components + c] = v;
    }
  }
  return std::nullopt;
}

Status read_indices(GltfContext& ctx, int index, std::size_t vertex_count,
                    const std::string& object, std::vector<std::uint32_t>& out) {
  Located at;
  if (auto e = locate(ctx, index, 1, object, "indices", at)) return e;
  const std::string name = indexed("accessors", std::size_t(index));
  const int ct = at.component_type;
  if (at.normalized || (ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                        ct != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    return ctx.fail(name, "componentType",
                    std::string("indices must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT, "
                                "not normalized; got ") + component_name(ct));
  const int csize = component_size(ct);
  if (at.stride != std::uint64_t(csize))
    return ctx.fail(indexed("bufferViews", std::size_t(ctx.model.accessors[std::size_t(index)].bufferView)),
                    "byteStride", "must not be set for an index buffer view");
  if (auto e = ctx.charge(at.count * sizeof(std::uint32_t), name)) return e;
  out.resize(at.count);
  for (std::uint64_t i = 0; i < at.count; ++i) {
    const unsigned char* p = at.data + i * at.stride;
    const std::uint32_t v = csize == 1 ? p[0] : csize == 2 ? load<std::uint16_t>(p) : load<std::uint32_t>(p);
    if (v >= vertex_count)
      return ctx.fail(object, "indices", name + " element " + std::to_string(i) + " is " +
                                             std::to_string(v) + ", but there are only " +
                                             std::to_string(vertex_count) + " vertices");
    out[i] = v;
  }
  return std::nullopt;
}

}  // namespace sss::scene
