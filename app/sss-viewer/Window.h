// The windowed viewer: a GLFW window (no client API) presenting the Renderer's display
// image through a vk::Swapchain, with the ImGui panels (Ui.h) drawn over it and the
// orbit camera (OrbitCamera.h) driven by the mouse.
#pragma once

#include "ViewerArgs.h"

#include "renderer/RenderOptions.h"
#include "scene/Scene.h"

namespace sss::app {

inline constexpr const char* kNoDisplayMessage =
    "no display available; use --headless --out FILE.png to render without a window";

// The size the window opens at for a requested width x height on a screen whose work area
// (glfwGetMonitorWorkarea: without task bars) is screen_w x screen_h: the request when it
// fits in 95% of it, else scaled down, keeping the aspect ratio, until it does (issue 20:
// "open at a size that fits the screen"). An unknown work area (0) keeps the request.
struct WindowSize {
  int width = 0, height = 0;
};
WindowSize fit_window_to_screen(int width, int height, int screen_w, int screen_h);

// Runs until the window closes, or for a.frames frames when a.screenshot is set (then
// saves it). Returns the exit code (DESIGN.md §4): 1 when there is no display or the
// device fails.
int run_window(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options);

}  // namespace sss::app
