// The windowed viewer: a GLFW window (no client API) presenting the Renderer's display
// image through a vk::Swapchain, with the ImGui panels (Ui.h) drawn over it and the
// orbit camera (OrbitCamera.h) driven by the mouse.
#pragma once

#include "ViewerArgs.h"

#include "renderer/RenderOptions.h"
#include "renderer/scene/Scene.h"

namespace sss::app {

inline constexpr const char* kNoDisplayMessage =
    "no display available; use --headless --out FILE.png to render without a window";

// Runs until the window closes, or for a.frames frames when a.screenshot is set (then
// saves it). Returns the exit code (DESIGN.md §4): 1 when there is no display or the
// device fails.
int run_window(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options);

}  // namespace sss::app
