// check_gltf_schema: the type of every glTF 2.0 property tinygltf reads, and every index
// into another array, checked on the raw JSON before tinygltf parses it.
//
// Why here and not after tinygltf: tinygltf 2.7.0 silently keeps a property's default
// when an optional property has the wrong type ("byteOffset": -4 reads as 0,
// "metallicFactor": "1" as 1.0, "pbrMetallicRoughness": [] as the default material), and
// it narrows every index to int (GetInt: static_cast<int>(int64), so "mesh": 4294967296
// reads as mesh 0). Either way a broken file would load as a different, valid one.
// The property names, types and enums are those of the glTF 2.0 JSON schema
// (https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html, §5 "Properties
// Reference") and of KHR_lights_punctual. Unknown properties are allowed (the spec
// allows them); `extensions` must be an object of objects; `extras` may be anything.
#include "scene/GltfJson.h"

#include <nlohmann/json.hpp>

#include <climits>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>

namespace sss::scene {

namespace {

using nlohmann::json;

std::string at(const std::string& array, std::size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

std::string join(const std::string& object, const std::string& field) {
  return object.empty() ? field : object + "." + field;
}

class Schema {
 public:
  Schema(const std::string& file, const json& root) : file_(file), root_(root) {}

  std::optional<LoadError> run() {
    count_arrays();
    if (!error_) check_root();
    return error_;
  }

 private:
  const std::string& file_;
  const json& root_;
  std::map<std::string, std::size_t> sizes_;  // "accessors" -> count, "lights" -> count
  std::optional<LoadError> error_;

  bool fail(const std::string& object, const std::string& field, std::string message) {
    if (!error_) error_ = LoadError{file_, object, field, std::move(message)};
    return false;
  }

  // --- one property of object `o` (named `name` in messages) -------------------------

  // o[key] when present, else nullptr; `required` fails when absent.
  const json* member(const json& o, const std::string& name, const char* key, bool required = false) {
    if (o.contains(key)) return &o.at(key);
    if (required) fail(name, key, "is required");
    return nullptr;
  }

  // An integer (JSON integer syntax, not 1.0) in [lo, hi].
  bool integer(const json& o, const std::string& name, const char* key, long long lo, long long hi,
               bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    const bool whole = v->is_number_integer() || v->is_number_unsigned();
    const bool in_range =
        whole && (v->is_number_unsigned()
                      ? v->get<std::uint64_t>() <= static_cast<std::uint64_t>(hi) &&
                            (lo <= 0 || v->get<std::uint64_t>() >= static_cast<std::uint64_t>(lo))
                      : v->get<std::int64_t>() >= lo && v->get<std::int64_t>() <= hi);
    if (!in_range)
      return fail(name, key, "must be an integer in [" + std::to_string(lo) + ", " +
                                 std::to_string(hi) + "], got " + v->dump());
    return true;
  }

  // A non-negative integer that tinygltf keeps as size_t (byteOffset, byteLength, count).
  bool size(const json& o, const std::string& name, const char* key, bool required = false,
            std::uint64_t min = 0) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    const bool ok = v->is_number_unsigned() ||
                    (v->is_number_integer() && v->get<std::int64_t>() >= 0);
    if (!ok) return fail(name, key, "must be a non-negative integer, got " + v->dump());
    if (v->get<std::uint64_t>() < min)
      return fail(name, key, "must be >= " + std::to_string(min) + ", got " + v->dump());
    return true;
  }

  bool index_value(const json& v, const std::string& name, const std::string& field,
                   const std::string& array) {
    const std::size_t n = sizes_.count(array) ? sizes_.at(array) : 0;
    const bool whole = v.is_number_integer() || v.is_number_unsigned();
    if (!whole || (v.is_number_integer() && v.get<std::int64_t>() < 0))
      return fail(name, field, "must be an index into " + array + " (an integer >= 0), got " + v.dump());
    const std::uint64_t i = v.get<std::uint64_t>();
    if (i >= n)
      return fail(name, field, array + "[" + std::to_string(i) + "] does not exist (the file has " +
                                   std::to_string(n) + ")");
    return true;
  }

  // An index into the top-level array `array` (or "lights").
  bool index(const json& o, const std::string& name, const char* key, const std::string& array,
             bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    return index_value(*v, name, key, array);
  }

  // An array of distinct indices into `array`.
  bool index_array(const json& o, const std::string& name, const char* key, const std::string& array,
                   bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    if (!v->is_array()) return fail(name, key, "must be an array of indices into " + array);
    std::set<std::uint64_t> seen;
    for (std::size_t k = 0; k < v->size(); ++k) {
      const std::string field = at(key, k);
      if (!index_value((*v)[k], name, field, array)) return false;
      if (!seen.insert((*v)[k].get<std::uint64_t>()).second)
        return fail(name, field, array + "[" + (*v)[k].dump() + "] is listed twice");
    }
    return true;
  }

  // A number: tinygltf reads these as double (JSON cannot hold NaN or Inf: the parser
  // refuses an overflowing literal). Range checks belong to the converters.
  bool number(const json& o, const std::string& name, const char* key, bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    if (!v->is_number()) return fail(name, key, "must be a number, got " + v->dump());
    return true;
  }

  // An array of numbers; exactly `n` of them unless n == 0.
  bool numbers(const json& o, const std::string& name, const char* key, std::size_t n) {
    const json* v = member(o, name, key);
    if (!v) return !error_;
    if (!v->is_array() || (n && v->size() != n))
      return fail(name, key, n ? "must be an array of " + std::to_string(n) + " numbers"
                               : std::string("must be an array of numbers"));
    for (std::size_t k = 0; k < v->size(); ++k)
      if (!(*v)[k].is_number()) return fail(name, at(key, k), "must be a number, got " + (*v)[k].dump());
    return true;
  }

  bool string(const json& o, const std::string& name, const char* key, bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    if (!v->is_string()) return fail(name, key, "must be a string, got " + v->dump());
    return true;
  }

  bool one_of(const json& o, const std::string& name, const char* key,
              std::initializer_list<const char*> allowed, bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    std::string list;
    for (const char* a : allowed) {
      if (v->is_string() && v->get<std::string>() == a) return true;
      list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
    }
    return fail(name, key, "must be one of " + list + ", got " + v->dump());
  }

  bool one_of(const json& o, const std::string& name, const char* key, std::initializer_list<int> allowed,
              bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return !error_;
    std::string list;
    for (int a : allowed) {
      if ((v->is_number_integer() || v->is_number_unsigned()) && v->get<std::int64_t>() == a) return true;
      list += (list.empty() ? "" : ", ") + std::to_string(a);
    }
    return fail(name, key, "must be one of " + list + ", got " + v->dump());
  }

  bool boolean(const json& o, const std::string& name, const char* key) {
    const json* v = member(o, name, key);
    if (!v) return !error_;
    if (!v->is_boolean()) return fail(name, key, "must be true or false, got " + v->dump());
    return true;
  }

  // o[key] as a JSON object (nullptr when absent or wrong; check error_).
  const json* object(const json& o, const std::string& name, const char* key, bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return nullptr;
    if (!v->is_object()) {
      fail(name, key, "must be a JSON object, got " + v->dump().substr(0, 40));
      return nullptr;
    }
    return v;
  }

  // o[key] as an array of JSON objects (nullptr when absent or wrong; check error_).
  const json* objects(const json& o, const std::string& name, const char* key, bool required = false) {
    const json* v = member(o, name, key, required);
    if (!v) return nullptr;
    if (!v->is_array()) {
      fail(name, key, "must be an array");
      return nullptr;
    }
    for (std::size_t i = 0; i < v->size(); ++i)
      if (!(*v)[i].is_object()) {
        fail(join(name, at(key, i)), "", "must be a JSON object");
        return nullptr;
      }
    return v;
  }

  // Common to every glTF object: name, extensions (an object of objects).
  bool common(const json& o, const std::string& name) { return string(o, name, "name") && extensions(o, name); }

  bool extensions(const json& o, const std::string& name) {
    const json* ext = object(o, name, "extensions");
    if (error_) return false;
    if (ext)
      for (const auto& item : ext->items())
        if (!item.value().is_object())
          return fail(name, "extensions." + item.key(), "must be a JSON object");
    return true;
  }

  // --- the document -------------------------------------------------------------------

  void count_arrays() {
    for (const char* key : {"accessors", "animations", "buffers", "bufferViews", "cameras", "images",
                            "materials", "meshes", "nodes", "samplers", "scenes", "skins", "textures"})
      if (const json* a = objects(root_, "", key)) sizes_[key] = a->size();
    const json* ext = object(root_, "", "extensions");
    const json* khr = ext ? object(*ext, "extensions", "KHR_lights_punctual") : nullptr;
    if (khr)
      if (const json* l = objects(*khr, "extensions.KHR_lights_punctual", "lights"))
        sizes_["KHR_lights_punctual.lights"] = l->size();
  }

  template <typename F>
  void each(const char* array, F&& check) {
    if (error_ || !root_.contains(array)) return;
    const json& a = root_.at(array);
    for (std::size_t i = 0; i < a.size() && !error_; ++i) {
      const std::string name = at(array, i);
      if (common(a[i], name)) check(a[i], name);
    }
  }

  // The root's own fields: asset, scene, extensionsUsed and extensionsRequired, extensions.
  bool check_top_level() {
    const json* asset = object(root_, "", "asset", true);
    if (!asset) return false;
    if (!string(*asset, "asset", "version", true) || !string(*asset, "asset", "minVersion") ||
        !string(*asset, "asset", "generator") || !string(*asset, "asset", "copyright"))
      return false;
    if (!index(root_, "", "scene", "scenes")) return false;
    for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
      const json* v = member(root_, "", key);
      if (!v) continue;
      if (!v->is_array()) {
        fail(key, "", "must be an array of strings");
        return false;
      }
      for (std::size_t k = 0; k < v->size(); ++k)
        if (!(*v)[k].is_string()) {
          fail(key, "[" + std::to_string(k) + "]", "must be a string");
          return false;
        }
    }
    return extensions(root_, "");
  }

  void buffer_view(const json& v, const std::string& n) {
    if (!index(v, n, "buffer", "buffers", true) || !size(v, n, "byteOffset") ||
        !size(v, n, "byteLength", true, 1) || !integer(v, n, "byteStride", 4, 252) ||
        !one_of(v, n, "target", {34962, 34963}))
      return;
    // EXT_meshopt_compression's README, "JSON schema updates"; the rules that tie
    // these fields together are checked in GltfJson.cpp.
    if (const json* e = find_extension(v, "EXT_meshopt_compression")) {
      const std::string en = n + ".extensions.EXT_meshopt_compression";
      index(*e, en, "buffer", "buffers", true) && size(*e, en, "byteOffset") &&
          size(*e, en, "byteLength", true, 1) && integer(*e, en, "byteStride", 1, 256, true) &&
          size(*e, en, "count", true, 1) &&
          one_of(*e, en, "mode", {"ATTRIBUTES", "TRIANGLES", "INDICES"}, true) &&
          one_of(*e, en, "filter", {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"});
    }
  }

  void check_root() {
    if (!check_top_level()) return;
    each("accessors", [&](const json& a, const std::string& n) { accessor(a, n); });
    each("animations", [&](const json& a, const std::string& n) { animation(a, n); });
    each("buffers", [&](const json& b, const std::string& n) {
      size(b, n, "byteLength", true, 1) && string(b, n, "uri");
      if (const json* e = find_extension(b, "EXT_meshopt_compression"))
        boolean(*e, n + ".extensions.EXT_meshopt_compression", "fallback");
    });
    each("bufferViews", [&](const json& v, const std::string& n) { buffer_view(v, n); });
    each("cameras", [&](const json& c, const std::string& n) { camera(c, n); });
    each("images", [&](const json& im, const std::string& n) {
      string(im, n, "uri") && index(im, n, "bufferView", "bufferViews") &&
          one_of(im, n, "mimeType", {"image/png", "image/jpeg"}, im.contains("bufferView"));
    });
    each("materials", [&](const json& m, const std::string& n) { material(m, n); });
    each("meshes", [&](const json& m, const std::string& n) { mesh(m, n); });
    each("nodes", [&](const json& nd, const std::string& n) { node(nd, n); });
    each("samplers", [&](const json& s, const std::string& n) {
      one_of(s, n, "magFilter", {9728, 9729}) &&
          one_of(s, n, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987}) &&
          one_of(s, n, "wrapS", {33071, 33648, 10497}) && one_of(s, n, "wrapT", {33071, 33648, 10497});
    });
    each("scenes", [&](const json& s, const std::string& n) { index_array(s, n, "nodes", "nodes"); });
    each("skins", [&](const json& s, const std::string& n) {
      index(s, n, "inverseBindMatrices", "accessors") && index(s, n, "skeleton", "nodes") &&
          index_array(s, n, "joints", "nodes", true);
    });
    each("textures", [&](const json& t, const std::string& n) {
      index(t, n, "sampler", "samplers") && index(t, n, "source", "images");
    });
    if (!error_ && sizes_.count("KHR_lights_punctual.lights")) {
      const json& lights = root_["extensions"]["KHR_lights_punctual"]["lights"];
      for (std::size_t i = 0; i < lights.size() && !error_; ++i)
        light(lights[i], "extensions.KHR_lights_punctual." + at("lights", i));
    }
  }

  void accessor(const json& a, const std::string& n) {
    if (!index(a, n, "bufferView", "bufferViews") || !size(a, n, "byteOffset") ||
        !one_of(a, n, "componentType", {5120, 5121, 5122, 5123, 5125, 5126}, true) ||
        !boolean(a, n, "normalized") || !size(a, n, "count", true, 1) ||
        !one_of(a, n, "type", {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, true) ||
        !numbers(a, n, "max", 0) || !numbers(a, n, "min", 0))
      return;
    const json* sparse = object(a, n, "sparse");
    if (!sparse) return;
    const std::string s = n + ".sparse";
    // tinygltf keeps the sparse count and offsets as int.
    if (!common(*sparse, s) || !integer(*sparse, s, "count", 1, INT_MAX, true)) return;
    const json* indices = object(*sparse, s, "indices", true);
    if (!indices || !common(*indices, s + ".indices") ||
        !index(*indices, s + ".indices", "bufferView", "bufferViews", true) ||
        !integer(*indices, s + ".indices", "byteOffset", 0, INT_MAX) ||
        !one_of(*indices, s + ".indices", "componentType", {5121, 5123, 5125}, true))
      return;
    const json* values = object(*sparse, s, "values", true);
    if (!values || !common(*values, s + ".values")) return;
    index(*values, s + ".values", "bufferView", "bufferViews", true) &&
        integer(*values, s + ".values", "byteOffset", 0, INT_MAX);
  }

  void animation(const json& a, const std::string& n) {
    const json* samplers = objects(a, n, "samplers", true);
    if (!samplers) return;
    for (std::size_t i = 0; i < samplers->size() && !error_; ++i) {
      const json& s = (*samplers)[i];
      const std::string sn = n + "." + at("samplers", i);
      common(s, sn) && index(s, sn, "input", "accessors", true) &&
          index(s, sn, "output", "accessors", true) &&
          one_of(s, sn, "interpolation", {"LINEAR", "STEP", "CUBICSPLINE"});
    }
    const json* channels = objects(a, n, "channels", true);
    if (!channels) return;
    const std::string samplers_name = n + ".samplers";
    sizes_[samplers_name] = samplers->size();
    for (std::size_t i = 0; i < channels->size() && !error_; ++i) {
      const json& c = (*channels)[i];
      const std::string cn = n + "." + at("channels", i);
      if (!common(c, cn) || !index(c, cn, "sampler", samplers_name, true)) return;
      const json* target = object(c, cn, "target", true);
      if (!target) return;
      common(*target, cn + ".target") && index(*target, cn + ".target", "node", "nodes") &&
          one_of(*target, cn + ".target", "path", {"translation", "rotation", "scale", "weights", "pointer"}, true);  // pointer: KHR_animation_pointer
    }
  }

  void camera(const json& c, const std::string& n) {
    if (!one_of(c, n, "type", {"perspective", "orthographic"}, true)) return;
    const bool persp = c["type"] == "perspective";
    const json* p = object(c, n, persp ? "perspective" : "orthographic", true);
    if (!p || !common(*p, join(n, persp ? "perspective" : "orthographic"))) return;
    const std::string pn = join(n, persp ? "perspective" : "orthographic");
    if (persp)
      number(*p, pn, "yfov", true) && number(*p, pn, "znear", true) && number(*p, pn, "zfar") &&
          number(*p, pn, "aspectRatio");
    else
      number(*p, pn, "xmag", true) && number(*p, pn, "ymag", true) && number(*p, pn, "znear", true) &&
          number(*p, pn, "zfar", true);
  }

  bool texture_info(const json& o, const std::string& name, const char* key, const char* extra_number) {
    const json* t = object(o, name, key);
    if (!t) return !error_;
    const std::string tn = join(name, key);
    // texCoord selects TEXCOORD_n: tinygltf keeps it as int.
    return common(*t, tn) && index(*t, tn, "index", "textures", true) &&
           integer(*t, tn, "texCoord", 0, INT_MAX) && (!extra_number || number(*t, tn, extra_number));
  }

  void material(const json& m, const std::string& n) {
    if (const json* pbr = object(m, n, "pbrMetallicRoughness")) {
      const std::string pn = n + ".pbrMetallicRoughness";
      if (!common(*pbr, pn) || !numbers(*pbr, pn, "baseColorFactor", 4) ||
          !texture_info(*pbr, pn, "baseColorTexture", nullptr) || !number(*pbr, pn, "metallicFactor") ||
          !number(*pbr, pn, "roughnessFactor") ||
          !texture_info(*pbr, pn, "metallicRoughnessTexture", nullptr))
        return;
    }
    if (error_) return;
    texture_info(m, n, "normalTexture", "scale") && texture_info(m, n, "occlusionTexture", "strength") &&
        texture_info(m, n, "emissiveTexture", nullptr) && numbers(m, n, "emissiveFactor", 3) &&
        one_of(m, n, "alphaMode", {"OPAQUE", "MASK", "BLEND"}) && number(m, n, "alphaCutoff") &&
        boolean(m, n, "doubleSided");
  }

  bool attributes(const json& o, const std::string& name, const char* key, bool required) {
    const json* attrs = object(o, name, key, required);
    if (!attrs) return !error_;
    for (const auto& item : attrs->items())
      if (!index_value(item.value(), name, std::string(key) + "." + item.key(), "accessors")) return false;
    return true;
  }

  void mesh(const json& m, const std::string& n) {
    if (!numbers(m, n, "weights", 0)) return;
    const json* prims = objects(m, n, "primitives", true);
    if (!prims) return;
    if (prims->empty()) {
      fail(n, "primitives", "must not be empty");
      return;
    }
    for (std::size_t p = 0; p < prims->size() && !error_; ++p) {
      const json& prim = (*prims)[p];
      const std::string pn = n + "." + at("primitives", p);
      if (!common(prim, pn) || !attributes(prim, pn, "attributes", true) ||
          !index(prim, pn, "indices", "accessors") || !index(prim, pn, "material", "materials"))
        return;
      if (prim.contains("mode") && !integer(prim, pn, "mode", 0, 6)) {
        error_->message = prim["mode"].dump() + " is not a glTF primitive mode (0..6)";
        return;
      }
      // KHR_draco_mesh_compression's README: the view of the compressed bytes, and each
      // semantic's Draco attribute id (a uint32, not an accessor index).
      if (const json* e = find_extension(prim, "KHR_draco_mesh_compression")) {
        const std::string en = pn + ".extensions.KHR_draco_mesh_compression";
        if (!index(*e, en, "bufferView", "bufferViews", true)) return;
        const json* ids = object(*e, en, "attributes", true);
        if (!ids) return;
        for (const auto& item : ids->items())
          if (!integer(*ids, en + ".attributes", item.key().c_str(), 0, 0xFFFFFFFFll)) return;
      }
      // A morph target is a map like attributes: semantic -> accessor.
      if (const json* targets = objects(prim, pn, "targets"))
        for (std::size_t t = 0; t < targets->size() && !error_; ++t)
          for (const auto& item : (*targets)[t].items())
            if (!index_value(item.value(), pn, at("targets", t) + "." + item.key(), "accessors")) return;
    }
  }

  void node(const json& nd, const std::string& n) {
    if (!index(nd, n, "camera", "cameras") || !index_array(nd, n, "children", "nodes") ||
        !index(nd, n, "skin", "skins") || !numbers(nd, n, "matrix", 16) || !index(nd, n, "mesh", "meshes") ||
        !numbers(nd, n, "rotation", 4) || !numbers(nd, n, "scale", 3) || !numbers(nd, n, "translation", 3) ||
        !numbers(nd, n, "weights", 0))
      return;
    // tinygltf reads TRS only when there is no matrix, so it would drop them silently.
    if (nd.contains("matrix") && (nd.contains("translation") || nd.contains("rotation") || nd.contains("scale"))) {
      fail(n, "matrix", "cannot be combined with translation, rotation or scale");
      return;
    }
    if (!nd.contains("extensions") || !nd["extensions"].contains("KHR_lights_punctual")) return;
    const json& l = nd["extensions"]["KHR_lights_punctual"];
    index(l, n + ".extensions.KHR_lights_punctual", "light", "KHR_lights_punctual.lights", true);
  }

  void light(const json& l, const std::string& n) {
    if (!common(l, n) || !one_of(l, n, "type", {"directional", "point", "spot"}, true) ||
        !numbers(l, n, "color", 3) || !number(l, n, "intensity") || !number(l, n, "range"))
      return;
    if (const json* spot = object(l, n, "spot"))  // absent: the extension's default cone
      common(*spot, n + ".spot") && number(*spot, n + ".spot", "innerConeAngle") &&
          number(*spot, n + ".spot", "outerConeAngle");
  }
};

}  // namespace

std::optional<LoadError> check_gltf_schema(const nlohmann::json& root, const std::string& file) {
  return Schema(file, root).run();
}

}  // namespace sss::scene
