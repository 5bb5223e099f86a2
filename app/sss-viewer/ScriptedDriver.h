// Every --test-* behaviour of the window (ViewerArgs' hidden options), in one place outside
// the viewer loop, which calls it at fixed points of each frame. The tests script the
// window through it; without those options every hook does nothing, and the loop is the
// user's.
#pragma once

#include "ViewerArgs.h"

#include <vulkan/vulkan.h>

#include <optional>
#include <string>

struct GLFWwindow;

namespace sss::renderer {
class Renderer;
}

namespace sss::app {

class ViewerTools;
class ViewerUi;
struct LiveState;

class ScriptedDriver {
 public:
  explicit ScriptedDriver(const ViewerArgs& a) : a_(a) {}

  // --test-edit: the material edit applied through the panel's code before the first
  // frame. False (with the message printed) where the panel refuses it.
  bool start(ViewerUi& ui) const;
  // --test-open: at frame 2, a file to open, as if dropped on the window.
  std::optional<std::string> open_request(int frames);
  // --test-resize (resize, minimize, restore over frames 1-4) and --test-resize-storm
  // (two of its 50 changes): before the frame reads its size.
  void before_size(GLFWwindow* window, int frames);
  // --test-resize: the framebuffer reported as 0x0 for two frames after minimizing
  // (Xvfb has no window manager, so iconify may do nothing there).
  void simulate_minimized(int& fb_w, int& fb_h);
  // --test-compare: at frame 2, the Compare button and the view asked for.
  void compare(int frames, ViewerTools& tools, const renderer::Renderer& r, const LiveState& live) const;
  // --test-interaction: every frame counts as interactive (scaled).
  bool interacting() const { return a_.test_interaction; }
  // --test-resize-storm: one more change while the frame is under way.
  void during_frame(GLFWwindow* window);
  // After frame `frames` was presented at `fb` on a swapchain of `extent`:
  // --test-host-oom frame throws std::bad_alloc at frame 2; the storm counts the frames
  // presented at the final size.
  void presented(int frames, VkExtent2D fb, VkExtent2D extent);
  // --test-compare: an exit status once the comparison failed (message printed).
  std::optional<int> failed(const ViewerTools& tools) const;
  // Whether --screenshot must wait past --frames: an edit still being refitted, a
  // comparison not done, a storm not settled.
  bool waiting(int frames, const ViewerUi& ui, const ViewerTools& tools) const;

 private:
  void storm_resize(GLFWwindow* window);

  const ViewerArgs& a_;
  bool opened_ = false;
  int simulated_minimized_ = 0;  // frames still reported as 0x0
  int storm_next_ = 0;           // changes made so far
  int frames_after_storm_ = 0;   // frames presented at the final size after the storm
};

}  // namespace sss::app
