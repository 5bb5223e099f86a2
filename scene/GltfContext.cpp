// GltfContext's budget and messages, and the buffer views every accessor relies on.
#include "scene/GltfContext.h"

#include <sstream>

namespace sss::scene {

Status GltfContext::charge(std::uint64_t bytes, const std::string& object) {
  if (bytes > options.max_scene_bytes || bytes_charged > options.max_scene_bytes - bytes)
    return fail(object, "", "the scene would need more than " +
                                std::to_string(options.max_scene_bytes) + " bytes (LoadOptions::max_scene_bytes)");
  bytes_charged += bytes;
  return std::nullopt;
}

std::optional<std::string> out_of_range(const char* array, long long index, std::size_t size) {
  if (index >= 0 && static_cast<unsigned long long>(index) < size) return std::nullopt;
  return std::string(array) + "[" + std::to_string(index) + "] does not exist (the file has " +
         std::to_string(size) + ")";
}

std::string number_text(double v) { return sss::message_number(v); }

Status check_buffer_views(GltfContext& ctx) {
  for (std::size_t i = 0; i < ctx.model.bufferViews.size(); ++i) {
    const tinygltf::BufferView& v = ctx.model.bufferViews[i];
    const std::string name = indexed("bufferViews", i);
    if (auto e = out_of_range("buffers", v.buffer, ctx.model.buffers.size()))
      return ctx.fail(name, "buffer", *e);
    const std::uint64_t size = ctx.model.buffers[std::size_t(v.buffer)].data.size();
    std::uint64_t end = 0;
    if (v.byteLength == 0) return ctx.fail(name, "byteLength", "must be >= 1");
    if (__builtin_add_overflow(std::uint64_t(v.byteOffset), std::uint64_t(v.byteLength), &end) ||
        end > size)
      return ctx.fail(name, "byteLength",
                      "bytes [" + std::to_string(v.byteOffset) + ", +" +
                          std::to_string(v.byteLength) + ") run past the " +
                          std::to_string(size) + " bytes of buffers[" + std::to_string(v.buffer) + "]");
    if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4 != 0))
      return ctx.fail(name, "byteStride", "must be a multiple of 4 in [4, 252], got " +
                                              std::to_string(v.byteStride));
  }
  return std::nullopt;
}

}  // namespace sss::scene
