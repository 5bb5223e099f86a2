// Moving bytes between the CPU and device-local resources through a staging buffer.
// Each call records one copy with its barriers, submits it (submit_once) and waits:
// for setup (meshes, textures, lookup tables) and for tests and readback of the final
// frame, not for per-frame streaming.
//
// The barriers around each copy are deliberately coarse (all earlier commands before
// the copy, all later commands after it), so a resource is safe to use in any later
// submission without more synchronisation.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

namespace sss::vk {

class Buffer;
class Context;
class Image;

// Writes `data` at `offset` into `dst` (any memory; needs TRANSFER_DST usage).
void upload_buffer(const Context& context, const Buffer& dst, std::span<const std::byte> data,
                   VkDeviceSize offset = 0);
// Reads `size` bytes from `offset` of `src` (needs TRANSFER_SRC usage).
std::vector<std::byte> download_buffer(const Context& context, const Buffer& src,
                                       VkDeviceSize offset = 0, VkDeviceSize size = VK_WHOLE_SIZE);

// Mip 0 of every layer, rows tightly packed, layer after layer: exactly
// width·height·layers·texel_size(format) bytes. The image's old contents are discarded;
// it is left in `final_layout`. Colour and depth-only formats (needs TRANSFER_DST).
void upload_image(const Context& context, const Image& dst, std::span<const std::byte> texels,
                  VkImageLayout final_layout);
// The same layout of bytes, read from an image in `layout` (which it is left in).
std::vector<std::byte> download_image(const Context& context, const Image& src,
                                      VkImageLayout layout);

// Typed conveniences.
template <typename T>
void upload_buffer(const Context& context, const Buffer& dst, std::span<const T> values,
                   VkDeviceSize offset = 0) {
  upload_buffer(context, dst, std::as_bytes(values), offset);
}
template <typename T>
std::vector<T> download_buffer_as(const Context& context, const Buffer& src, std::size_t count,
                                  VkDeviceSize offset = 0) {
  const std::vector<std::byte> bytes = download_buffer(context, src, offset, count * sizeof(T));
  std::vector<T> values(count);
  std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

}  // namespace sss::vk
