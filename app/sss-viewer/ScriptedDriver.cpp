#include "ScriptedDriver.h"

#include "ExitCodes.h"
#include "Tools.h"
#include "Ui.h"

#include "renderer/Renderer.h"

#include <GLFW/glfw3.h>

#include <iostream>
#include <new>

namespace sss::app {

namespace {

// --test-resize-storm: the sizes, in order; three per loop iteration.
constexpr int kStorm[10][2] = {{1, 1},     {2000, 1200}, {37, 611}, {640, 360}, {2, 3},
                               {1280, 720}, {321, 177},  {1, 400},  {900, 1},   {160, 90}};
constexpr int kStormChanges = 50;

}  // namespace

bool ScriptedDriver::start(ViewerUi& ui) const {
  if (a_.test_edit.empty() || ui.script_edit(a_.test_edit)) return true;
  std::cerr << "sss-viewer: error: --test-edit: expected preset=NAME, model=NAME or layers=FILE.json, got '"
            << a_.test_edit << "'\n";
  return false;
}

std::optional<std::string> ScriptedDriver::open_request(int frames) {
  if (a_.test_open.empty() || frames != 2 || opened_) return std::nullopt;
  opened_ = true;
  return a_.test_open;
}

void ScriptedDriver::storm_resize(GLFWwindow* window) {
  if (storm_next_ >= kStormChanges) return;
  const int* size = kStorm[storm_next_ % 10];
  glfwSetWindowSize(window, size[0], size[1]);
  if (++storm_next_ == kStormChanges) glfwSetWindowSize(window, a_.width, a_.height);
}

void ScriptedDriver::before_size(GLFWwindow* window, int frames) {
  if (a_.test_resize) {
    if (frames == 1) glfwSetWindowSize(window, a_.width + 64, a_.height + 36);
    if (frames == 2 && simulated_minimized_ == 0) {
      glfwIconifyWindow(window);
      simulated_minimized_ = 3;
    }
    if (frames == 3) glfwRestoreWindow(window);
    if (frames == 4) glfwSetWindowSize(window, a_.width, a_.height);
  }
  if (a_.test_resize_storm) {  // two changes before this frame's size is read
    storm_resize(window);
    storm_resize(window);
  }
}

void ScriptedDriver::simulate_minimized(int& fb_w, int& fb_h) {
  if (simulated_minimized_ > 1) {
    --simulated_minimized_;
    fb_w = fb_h = 0;
  }
}

void ScriptedDriver::compare(int frames, ViewerTools& tools, const renderer::Renderer& r,
                             const LiveState& live) const {
  if (a_.test_compare.empty() || frames != 2 || tools.reference_running() || tools.metrics()) return;
  tools.start_reference(r, live);
  tools.set_view(a_.test_compare == "split" ? 1 : a_.test_compare == "reference" ? 2 : 3, 0.5f);
  if (a_.test_compare == "log-ratio") tools.set_error_map(ViewerTools::ErrorMap::LogRatio);
}

void ScriptedDriver::during_frame(GLFWwindow* window) {
  if (a_.test_resize_storm) storm_resize(window);
}

void ScriptedDriver::presented(int frames, VkExtent2D fb, VkExtent2D extent) {
  if (frames == 2 && a_.test_host_oom == "frame") throw std::bad_alloc();
  if (a_.test_resize_storm && storm_next_ >= kStormChanges && int(fb.width) == a_.width &&
      int(fb.height) == a_.height && extent.width == fb.width && extent.height == fb.height)
    ++frames_after_storm_;
}

std::optional<int> ScriptedDriver::failed(const ViewerTools& tools) const {
  if (a_.test_compare.empty() || tools.compare_error().empty()) return std::nullopt;
  std::cerr << "sss-viewer: error: compare: " << tools.compare_error() << '\n';
  return kExitRuntime;
}

bool ScriptedDriver::waiting(int frames, const ViewerUi& ui, const ViewerTools& tools) const {
  const bool editing = !a_.test_edit.empty() && ui.busy();
  const bool comparing = !a_.test_compare.empty() && (frames <= 2 || !tools.metrics());
  const bool storming = a_.test_resize_storm && frames_after_storm_ < a_.frames;
  return editing || comparing || storming;
}

}  // namespace sss::app
