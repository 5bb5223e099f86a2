// load_gltf: the order of checks. (1) The file is read with a size cap. (2) A GLB's
// container is checked and rebuilt from its checked chunks. (3) The JSON is checked for depth, URIs, image views and
// extras.sss before tinygltf sees it, and every property's type and every index
// (GltfSchema.cpp). (4) tinygltf parses with file access confined to
// the file's folder and image decoding deferred; any error or warning it reports fails
// the load. (5) The model is converted part by part, each checked before use.
#include "scene/GltfLoader.h"

#include "scene/GltfContext.h"
#include "scene/GltfFile.h"
#include "scene/GltfJson.h"
#include "scene/GltfUri.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <new>

namespace sss::scene {

namespace {

// The image hook: keeps the encoded bytes of URI images (tinygltf read them through
// the sandbox or decoded a checked data URI) and never decodes. Images in buffer views
// are ignored here: their pointer is not trusted, and their bytes are taken from the
// checked view later.
bool capture_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                   const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0 || index < 0 || size <= 0 || bytes == nullptr) return true;
  auto& store = *static_cast<std::vector<std::vector<unsigned char>>*>(user);
  if (store.size() <= std::size_t(index)) store.resize(std::size_t(index) + 1);
  store[std::size_t(index)].assign(bytes, bytes + size);
  return true;
}

// tinygltf's messages, one line each, trimmed to a readable length.
std::string summarize(const std::string& err, const std::string& warn) {
  std::string all = err + (err.empty() || warn.empty() ? "" : "\n") + warn;
  while (!all.empty() && (all.back() == '\n' || all.back() == ' ')) all.pop_back();
  std::replace(all.begin(), all.end(), '\n', ';');
  if (all.size() > 600) all = all.substr(0, 600) + "...";
  return all;
}

Status check_extensions(const GltfContext& ctx) {
  for (std::size_t i = 0; i < ctx.model.extensionsRequired.size(); ++i) {
    const std::string& ext = ctx.model.extensionsRequired[i];
    if (!is_supported_required_extension(ext))
      return ctx.fail("extensionsRequired", "[" + std::to_string(i) + "]",
                      "\"" + ext + "\" is required by the file but not supported");
  }
  if (ctx.model.asset.version != "2.0")
    return ctx.fail("asset", "version", "must be \"2.0\", got \"" + ctx.model.asset.version + "\"");
  return std::nullopt;
}

namespace {

// Every file a URI names exists inside the folder, said here with the object and field;
// tinygltf would only say "File not found" (and only warn for an image).
std::optional<LoadError> check_file_uris(const std::string& path, const GltfJsonFacts& facts,
                                         const FileSandbox& sandbox) {
  std::error_code ec;
  for (const auto& [object, uri] : facts.file_uris) {
    const std::string file = (sandbox.root / decode_file_uri(uri)).string();  // tinygltf's JoinPath
    if (!std::filesystem::exists(file, ec))
      return LoadError{path, object, "uri", "\"" + uri + "\": no such file in " + sandbox.root.string()};
    if (!std::filesystem::is_regular_file(file, ec))
      return LoadError{path, object, "uri", "\"" + uri + "\" is not a regular file"};
    if (!sandbox.resolves_inside(file))
      return LoadError{path, object, "uri", "\"" + uri + "\" leads out of the glTF file's folder (a link)"};
  }
  return std::nullopt;
}

// tinygltf's parse of the checked JSON (or GLB), its files read through the sandbox and its
// images captured undecoded into uri_images; "" on success, else the message (any error
// or warning of tinygltf's fails the load).
std::string parse_model(FileSandbox& sandbox, bool glb, const std::vector<unsigned char>& glb_bytes,
                        std::string_view json, tinygltf::Model& model,
                        std::vector<std::vector<unsigned char>>& uri_images) {
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks(sandbox_callbacks(&sandbox));
  parser.SetImageLoader(&capture_image, &uri_images);
  std::string err, warn;
  const std::string base = sandbox.root.string();
  const bool ok = glb ? parser.LoadBinaryFromMemory(&model, &err, &warn, glb_bytes.data(),
                                                    static_cast<unsigned>(glb_bytes.size()), base)
                      : parser.LoadASCIIFromString(&model, &err, &warn, json.data(),
                                                   static_cast<unsigned>(json.size()), base);
  if (ok && err.empty() && warn.empty()) return "";
  const std::string what = summarize(err, warn);
  return "tinygltf: " + (what.empty() ? std::string("failed without a message") : what);
}

// The JSON to check and, for a GLB, the checked chunks as tinygltf will see them. The
// views point into the file's bytes.
struct GltfSource {
  bool glb = false;
  std::string_view json;
  std::vector<unsigned char> glb_bytes;
  std::optional<std::uint64_t> bin_bytes;
  GlbLayout layout;
};

// A GLB (by its magic or extension) is split into its chunks; a .gltf is its JSON.
std::variant<GltfSource, LoadError> split_source(const std::string& path, const std::vector<unsigned char>& bytes,
                                                 const LoadOptions& options) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  GltfSource src;
  src.glb = has_glb_magic(bytes) || ext == ".glb";
  if (src.glb) {
    auto layout = parse_glb(bytes);
    if (auto* e = std::get_if<FieldError>(&layout)) return LoadError{path, "glb", e->field, e->message};
    src.layout = std::get<GlbLayout>(layout);
    src.json = src.layout.json;
    src.bin_bytes = src.layout.bin.size();
    src.glb_bytes = rebuild_glb(src.layout);
    if (src.glb_bytes.size() > std::numeric_limits<unsigned>::max())
      return LoadError{path, "", "", "is too large for a GLB"};
  } else {
    src.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  if (src.json.size() > options.max_json_bytes)
    return LoadError{path, "", "",
                     "its JSON is " + std::to_string(src.json.size()) + " bytes, more than the limit of " +
                         std::to_string(options.max_json_bytes) + " (LoadOptions::max_json_bytes)"};
  return src;
}

// tinygltf's model into the scene, stage by stage; the first error stops it.
std::optional<LoadError> convert_model(GltfContext& ctx, tinygltf::Model& model, const GltfJsonFacts& f) {
  if (auto e = check_extensions(ctx)) return e;
  if (auto e = decode_meshopt(ctx, model, f)) return e;
  if (auto e = check_buffer_views(ctx)) return e;
  if (auto e = convert_materials(ctx, f)) return e;
  if (auto e = convert_meshes(ctx)) return e;
  return convert_nodes(ctx);
}

}  // namespace

std::variant<Scene, LoadError> load(const std::string& path, const LoadOptions& options) {
  const auto fail = [&](std::string field, std::string message) {
    return LoadError{path, "", std::move(field), std::move(message)};
  };
  // tinygltf takes the size as unsigned int.
  const std::uint64_t max_bytes =
      std::min<std::uint64_t>(options.max_file_bytes, std::numeric_limits<unsigned>::max());
  auto read = read_file_capped(path, max_bytes);
  if (auto* msg = std::get_if<std::string>(&read)) return fail("", *msg);
  const std::vector<unsigned char>& bytes = std::get<std::vector<unsigned char>>(read);
  auto split = split_source(path, bytes, options);
  if (auto* e = std::get_if<LoadError>(&split)) return *e;
  GltfSource& src = std::get<GltfSource>(split);
  auto facts = check_gltf_json(src.json, path, src.bin_bytes);
  if (auto* e = std::get_if<LoadError>(&facts)) return *e;
  if (const auto& parser_json = std::get<GltfJsonFacts>(facts).parser_json) {
    src.json = *parser_json;  // placeholder buffers stand in as 1-byte data URIs
    if (src.glb) src.glb_bytes = rebuild_glb(GlbLayout{src.json, src.layout.bin});
  }

  std::error_code ec;
  FileSandbox sandbox;
  sandbox.root = std::filesystem::absolute(std::filesystem::path(path), ec).parent_path().lexically_normal();
  if (ec) return fail("", "cannot resolve its folder: " + ec.message());
  sandbox.max_file_bytes = max_bytes;
  sandbox.bytes_left = options.max_external_bytes;
  if (auto e = check_file_uris(path, std::get<GltfJsonFacts>(facts), sandbox)) return *e;
  std::vector<std::vector<unsigned char>> uri_images;
  tinygltf::Model model;
  if (std::string why = parse_model(sandbox, src.glb, src.glb_bytes, src.json, model, uri_images); !why.empty())
    return fail("", why);

  Scene scene;
  scene.name = std::filesystem::path(path).stem().string();
  scene.mm_per_unit = options.mm_per_unit;
  const GltfJsonFacts& f = std::get<GltfJsonFacts>(facts);
  GltfContext ctx{path, options, model, scene, uri_images, f.image_media_type, f.draco, 0, {}, {}, {}, false, {}};
  ctx.mesh_quantization = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(),
                                    "KHR_mesh_quantization") != model.extensionsUsed.end();
  if (auto e = convert_model(ctx, model, f)) return *e;
  const Bounds b = scene.bounds();
  if (!b.empty() && !(std::isfinite(b.radius())))
    return fail("", "the scene's extent overflows float precision");
  if (options.add_camera_if_missing) add_camera_if_missing(scene);
  if (options.add_light_if_missing) add_light_if_missing(scene);
  return scene;
}

}  // namespace

std::variant<Scene, LoadError> load_gltf(const std::string& path, const LoadOptions& options) {
  try {
    return load(path, options);
  } catch (const std::bad_alloc&) {
    return LoadError{path, "", "", "out of memory while loading"};
  } catch (const std::exception& e) {
    return LoadError{path, "", "", std::string("unexpected failure: ") + e.what()};
  }
}

}  // namespace sss::scene
