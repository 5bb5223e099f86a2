// What the headless path, the window's --screenshot / --stats and the Screenshot panel
// share: writing the frame to a file, and the per-pass table of --stats.
#pragma once

#include "CliSupport.h"
#include "ViewerArgs.h"

#include "renderer/Renderer.h"
#include "image/Image.h"
#include "renderer/vk/Context.h"

#include <cstdio>
#include <iostream>
#include <string>

namespace sss::app {

// FILE.exr: the linear HDR frame; any other name: the tonemapped display PNG. Written
// atomically (image::write_*); throws image::WriteError naming the path.
inline void write_frame(const renderer::Renderer& r, const std::string& path) {
  if (lower_extension(path) == ".exr")
    image::write_exr(path, r.read_hdr());
  else
    image::write_png(path, r.read_display());
}

// --no-specular: the linear frame less its specular target, where the frame has geometry
// (the specular target is not cleared behind the background, which stays as read_hdr()'s).
inline image::Image frame_less_specular(const renderer::Renderer& r) {
  image::Image hdr = r.read_hdr(), specular = r.read_specular();
  for (std::size_t i = 0; i < specular.rgba.size(); i += 4)
    if (!(hdr.rgba[i + 3] > 0.5f)) specular.rgba[i] = specular.rgba[i + 1] = specular.rgba[i + 2] = 0.0f;
  return image::subtract_rgb(hdr, specular);
}

// The Vulkan context of a headless run (a frame, --frames N, --soak): --device and
// --validation (with synchronization checks, as SSS_VALIDATION=1).
inline vk::ContextOptions headless_context_options(const ViewerArgs& a) {
  vk::ContextOptions o;
  o.device_name = a.device;
  o.enable_validation = o.sync_validation = a.validation;
  return o;
}

// The renderer's warnings, and a note for each UV atlas texture space generated.
inline void print_warnings(const renderer::Renderer& r) {
  print_messages("sss-viewer", "warning", r.warnings());
  print_messages("sss-viewer", "note", r.atlas_notes());
}

// "pass  gpu ms" rows, then the GPU total and the renderer's CPU frame time.
inline void print_pass_times(const renderer::FrameStats& s) {
  std::printf("%-16s %10s\n", "pass", "gpu ms");
  for (const vk::PassTime& p : s.passes) std::printf("%-16s %10.3f\n", p.name.c_str(), p.ms);
  std::printf("%-16s %10.3f\n", "gpu total", s.gpu_ms);
  std::printf("%-16s %10.3f\n", "cpu frame", s.cpu_ms);
}

// The frame targets' device memory (Renderer::target_bytes), in MiB.
inline void print_target_memory(const renderer::Renderer& r) {
  std::printf("%-16s %10.1f MiB\n", "frame targets", double(r.target_bytes()) / (1024.0 * 1024.0));
}

}  // namespace sss::app
