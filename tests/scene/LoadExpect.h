// The loader tests' checks: a file that must load (its scene) or must not (its error's
// text), and a small PNG to embed in a test file.
#pragma once

#include "scene/GltfLoader.h"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

namespace sss::scene::testing {

inline Scene load_ok(const std::filesystem::path& path) {
  auto r = load_gltf(path.string());
  if (auto* e = std::get_if<LoadError>(&r)) ADD_FAILURE() << e->what();
  return r.index() == 0 ? std::get<Scene>(std::move(r)) : Scene{};
}

inline std::string load_error(const std::filesystem::path& path) {
  auto r = load_gltf(path.string());
  if (auto* e = std::get_if<LoadError>(&r)) return e->what();
  ADD_FAILURE() << path << " loaded but should not have";
  return {};
}

// A 2×2 RGB PNG: red, green / blue, white.
inline std::vector<unsigned char> tiny_png() {
  std::vector<unsigned char> png;
  const unsigned char pixels[2 * 2 * 3] = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255};
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(ctx);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
      },
      &png, 2, 2, 3, pixels, 6);
  return png;
}

}  // namespace sss::scene::testing
