#include "Window.h"

#include "ExitCodes.h"
#include "CliSupport.h"
#include "FrameOutput.h"
#include "InputFiles.h"
#include "OrbitCamera.h"
#include "Presenter.h"
#include "ScriptedDriver.h"
#include "Tools.h"
#include "Ui.h"

#include "renderer/Renderer.h"
#include "image/Image.h"
#include "scene/BuiltinScenes.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Context.h"

#define GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <new>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::app {

namespace {

bool has_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x != nullptr && *x != '\0') || (w != nullptr && *w != '\0');
}

int no_display() {
  std::cerr << "sss-viewer: error: " << kNoDisplayMessage << '\n';
  return kExitRuntime;
}

// GLFW: initialised, terminated at scope exit.
struct Glfw {
  bool ok = false;
  Glfw() { ok = glfwInit() == GLFW_TRUE; }
  ~Glfw() {
    if (ok) glfwTerminate();
  }
  Glfw(const Glfw&) = delete;
  Glfw& operator=(const Glfw&) = delete;
};

struct WindowHandle {
  GLFWwindow* window = nullptr;
  ~WindowHandle() {
    if (window != nullptr) glfwDestroyWindow(window);
  }
};

// Dear ImGui's context and backends, shut down in reverse order.
struct ImGuiSession {
  bool glfw = false, vulkan = false;
  ImGuiSession() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the working directory
    ImGui::StyleColorsDark();
  }
  ~ImGuiSession() {
    if (vulkan) ImGui_ImplVulkan_Shutdown();
    if (glfw) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
};

// Mouse and keys -> orbit camera, unless ImGui wants them.
void drive_camera(GLFWwindow* window, OrbitCamera& camera, bool& r_was_down, float width,
                  float height) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureMouse) {
    const bool shift = io.KeyShift;
    const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool valid = dx > -1e6f && dy > -1e6f;  // -FLT_MAX when the mouse was not seen
    if (valid && io.MouseDown[0] && !shift) camera.orbit(dx, dy);
    if (valid && (io.MouseDown[2] || (io.MouseDown[0] && shift))) camera.pan(dx, dy, width, height);
    if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
  }
  const bool r_down = glfwGetKey(window, GLFW_KEY_R) == GLFW_PRESS;
  if (r_down && !r_was_down && !io.WantCaptureKeyboard) camera.reset();
  r_was_down = r_down;
}

// Files dropped on the window since the last frame (GLFW calls back from glfwPollEvents
// on this thread).
std::vector<std::string>& dropped_files() {
  static std::vector<std::string> files;
  return files;
}

// What belongs to one loaded scene; opening another file replaces all of it.
struct Session {
  scene::Scene scene;
  std::string source;  // the path or builtin:NAME it came from
  std::unique_ptr<renderer::Renderer> renderer;
  std::unique_ptr<OrbitCamera> camera;
  std::unique_ptr<ViewerUi> ui;
  std::vector<std::filesystem::path> inputs;  // its files: never written over
  bool framed = false;  // the camera's home is set beside the panel (first frame)
};

std::unique_ptr<Session> make_session(const vk::Context& ctx, scene::Scene scene, std::string source,
                                      const renderer::RenderOptions& options) {
  auto s = std::make_unique<Session>();
  s->scene = std::move(scene);
  s->source = std::move(source);
  s->renderer = std::make_unique<renderer::Renderer>(ctx, s->scene, options);
  s->camera = std::make_unique<OrbitCamera>(s->renderer->camera(), s->scene.bounds());
  s->ui = std::make_unique<ViewerUi>(s->scene, options.separable_taps, options.single_scattering);
  s->inputs = scene_input_files(s->source);
  s->ui->set_protected_files(s->inputs);
  return s;
}

std::string window_title(const scene::Scene& scene, const std::string& source) {
  return "sss-viewer - " + (scene.name.empty() ? source : scene.name);
}

// Loads `path` as the viewer's command line would (a missing camera or light is added;
// the environment light stays the one shown) and builds its renderer with the current
// options. On failure the current session stays and the message says why.
std::unique_ptr<Session> open_scene(const vk::Context& ctx, const std::string& path,
                                    const renderer::RenderOptions& options,
                                    const std::optional<scene::Environment>& environment,
                                    std::string& message) {
  auto loaded = scene::load_scene(path);
  if (auto* e = std::get_if<scene::LoadError>(&loaded)) {
    message = e->what();
    return nullptr;
  }
  scene::Scene scene = std::move(std::get<scene::Scene>(loaded));
  scene::add_camera_if_missing(scene);
  scene::add_light_if_missing(scene);
  scene.environment = environment;
  try {
    auto s = make_session(ctx, std::move(scene), path, options);
    message = "opened " + path;
    for (const std::string& w : s->scene.warnings) message += "\nwarning: " + w;
    for (const std::string& w : s->renderer->warnings()) message += "\nwarning: " + w;
    for (const std::string& n : s->renderer->atlas_notes()) message += "\nnote: " + n;
    return s;
  } catch (const std::exception& e) {
    message = path + ": " + e.what();
    return nullptr;
  }
}

}  // namespace

WindowSize fit_window_to_screen(int width, int height, int screen_w, int screen_h) {
  if (screen_w <= 0 || screen_h <= 0 || width <= 0 || height <= 0) return {width, height};
  const double room = 0.95;  // the title bar and the window's border
  const double k = std::min({1.0, room * screen_w / width, room * screen_h / height});
  return {std::max(1, int(std::floor(width * k))), std::max(1, int(std::floor(height * k)))};
}

namespace {

// A window of the size asked for, or smaller where the screen is (--screenshot keeps the
// size asked for, which is the saved image's); null where none can be made.
GLFWwindow* open_window(const ViewerArgs& a, const std::string& title) {
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  WindowSize open_size{a.width, a.height};
  if (a.screenshot.empty())
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) {
      int x = 0, y = 0, w = 0, h = 0;
      glfwGetMonitorWorkarea(monitor, &x, &y, &w, &h);
      open_size = fit_window_to_screen(a.width, a.height, w, h);
      if (open_size.width != a.width || open_size.height != a.height)
        std::cerr << "sss-viewer: note: " << a.width << "x" << a.height << " does not fit the "
                  << w << "x" << h << " screen: the window opens at " << open_size.width << "x"
                  << open_size.height << '\n';
    }
  return glfwCreateWindow(open_size.width, open_size.height, title.c_str(), nullptr, nullptr);
}

// The Vulkan context for `window`: its surface, the swapchain extension, --device and
// --validation.
vk::ContextOptions window_context_options(const ViewerArgs& a, GLFWwindow* window) {
  vk::ContextOptions co;
  co.device_name = a.device;
  co.enable_validation = a.validation;
  co.sync_validation = a.validation;
  co.application_name = "sss-viewer";
  uint32_t ext_count = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&ext_count);
  for (uint32_t i = 0; i < ext_count; ++i) co.instance_extensions.emplace_back(exts[i]);
  co.device_extensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  co.create_surface = [window](VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    if (glfwCreateWindowSurface(instance, window, nullptr, &surface) != VK_SUCCESS)
      return VkSurfaceKHR{VK_NULL_HANDLE};
    return surface;
  };
  return co;
}

// The viewer loop's state across frames, and what --stats prints at the end.
struct LoopState {
  int fb_w = 0, fb_h = 0;  // the window's framebuffer
  int frames = 0;
  double frame_ms = 0.0, timed_ms = 0.0;
  int timed_frames = 0;
  bool r_was_down = false;
  std::optional<std::string> open_request_ui;  // from the Tools window, for the next frame
  std::uint64_t allocations_at_first_frame = 0;  // device-memory allocations (--stats)
  std::chrono::steady_clock::time_point last_interaction{};
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
};

// A file dropped, asked for by the Tools window's Open, or scripted: the session replaced
// by one of it, or the message why not (the scene shown stays).
void open_requested(const vk::Context& ctx, GLFWwindow* window, const Presenter& presenter,
                    std::unique_ptr<Session>& session, ViewerTools& tools, const std::string& path,
                    const LoopState& loop) {
  // The frame in flight reads the old renderer's display image: wait for it first.
  presenter.wait();
  std::string message;
  renderer::RenderOptions next_options = session->renderer->options();
  next_options.width = uint32_t(std::max(loop.fb_w, 1));  // full size, whatever was drawn last
  next_options.height = uint32_t(std::max(loop.fb_h, 1));
  auto next = open_scene(ctx, path, next_options, session->scene.environment, message);
  const bool failed = next == nullptr;
  if (next) {
    next->ui->set_interactive_scale(session->ui->interactive_scale());
    tools.reset();
    session = std::move(next);  // the old renderer goes here, its frame finished
    glfwSetWindowTitle(window, window_title(session->scene, session->source).c_str());
  }
  std::cerr << "sss-viewer: " << (failed ? "error: " : "") << message << '\n';
  tools.set_message(message, failed);
}

// Interactive resolution: while the view moves or a widget is dragged, render at
// ui.interactive_scale() of the window and let the blit upscale; the full-size frame
// comes back 0.3 s after the last change. --screenshot frames are always full size
// (unless --test-interaction, which times the scaled frames).
void size_for_interaction(renderer::Renderer& r, const ViewerUi& ui, VkExtent2D fb, bool moved,
                          bool screenshot, bool scripted, LoopState& loop) {
  const auto now = std::chrono::steady_clock::now();
  if ((!screenshot && (moved || ImGui::IsAnyItemActive())) || scripted) loop.last_interaction = now;
  const float scale = ui.interactive_scale();
  const bool scaled = scale < 1.0f && now - loop.last_interaction < std::chrono::milliseconds(300);
  const VkExtent2D render_size =
      scaled ? VkExtent2D{std::max(1u, uint32_t(std::lround(float(fb.width) * scale))),
                          std::max(1u, uint32_t(std::lround(float(fb.height) * scale)))}
             : fb;
  if (render_size.width != r.options().width || render_size.height != r.options().height)
    r.resize(render_size.width, render_size.height);
}

// The panels and the camera for one frame; the Tools window's Open is kept for the next.
void draw_panels(GLFWwindow* window, const Presenter& presenter, Session& session, ViewerTools& tools,
                 ScriptedDriver& script, VkExtent2D fb, bool screenshot, LoopState& loop) {
  renderer::Renderer& r = *session.renderer;
  OrbitCamera& camera = *session.camera;
  ViewerUi& ui = *session.ui;
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  drive_camera(window, camera, loop.r_was_down, float(fb.width), float(fb.height));
  // One frame in flight: the previous blit and UI pass finish before the panels may
  // change (or read back) the renderer's resources.
  presenter.wait();
  ui.draw(r, loop.frame_ms);
  if (!session.framed) {
    // The first frame of a scene: with the panel open, the subject moves into the part
    // of the window it leaves free. --screenshot keeps the scene's camera, so that it
    // stays the headless frame.
    session.framed = true;
    if (!screenshot) camera.frame_free_area(ui.panel_right(), float(fb.width), float(fb.height));
  }
  LiveState live{&session.scene, session.source, ui.editor().applied(), ui.lights(),
                 fb.width, fb.height, &session.inputs};
  script.compare(loop.frames, tools, r, live);
  if (std::optional<std::string> path = tools.draw(r, live)) loop.open_request_ui = *path;
  ImGui::Render();
}

// After a frame was presented: the frame time, for the panel and --stats.
void count_frame(const vk::Context& ctx, ViewerUi& ui, LoopState& loop) {
  ++loop.frames;
  if (loop.frames == 1) loop.allocations_at_first_frame = ctx.successful_allocations();
  const auto now = std::chrono::steady_clock::now();
  loop.frame_ms = std::chrono::duration<double, std::milli>(now - loop.last).count();
  loop.last = now;
  ui.frame_presented(loop.frame_ms);
  if (loop.frames > 1) {  // the first frame includes start-up
    loop.timed_ms += loop.frame_ms;
    ++loop.timed_frames;
  }
}

void print_window_stats(const vk::Context& ctx, const Presenter& presenter, const Session& session,
                        const ViewerTools& tools, const LoopState& loop) {
  const renderer::Renderer& r = *session.renderer;
  const VkPresentModeKHR mode = presenter.present_mode();
  std::printf("window %dx%d (rendered %ux%u), sss %s, present %s, %d frame(s)\n", loop.fb_w,
              loop.fb_h, r.options().width, r.options().height,
              std::string(renderer::technique_name(r.options().technique)).c_str(),
              mode == VK_PRESENT_MODE_FIFO_KHR ? "fifo" : mode == VK_PRESENT_MODE_MAILBOX_KHR ? "mailbox" : "immediate",
              loop.frames);
  print_pass_times(r.stats());
  if (loop.timed_frames > 0) {
    std::printf("%-16s %10.3f\n", "window frame", loop.timed_ms / loop.timed_frames);
    std::printf("%-16s %10.1f\n", "fps", 1000.0 * loop.timed_frames / loop.timed_ms);
  }
  print_target_memory(r);
  session.ui->print_stats(stdout);
  std::printf("%-16s %10llu\n", "allocations", static_cast<unsigned long long>(ctx.successful_allocations()));
  std::printf("%-16s %10llu\n", "allocations @1", static_cast<unsigned long long>(loop.allocations_at_first_frame));
  if (const auto& m = tools.metrics())
    std::printf("compare: relative RMSE %.6f, PSNR %.2f dB, SSIM %.4f, max abs %.4f\n", m->relative_rmse,
                m->psnr_db, m->ssim, m->max_abs_error);
}

// The viewer loop: until the window closes, or --screenshot's frames are done. Returns
// an exit status where a scripted comparison failed.
std::optional<int> viewer_loop(const ViewerArgs& a, const vk::Context& ctx, GLFWwindow* window,
                               Presenter& presenter, std::unique_ptr<Session>& session,
                               ViewerTools& tools, ScriptedDriver& script, LoopState& loop) {
  const bool screenshot = !a.screenshot.empty();
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    std::optional<std::string> open_request = std::move(loop.open_request_ui);
    loop.open_request_ui.reset();
    if (!dropped_files().empty()) {
      open_request = dropped_files().back();  // several at once: the last one
      dropped_files().clear();
    }
    if (auto scripted = script.open_request(loop.frames)) open_request = scripted;
    if (open_request) open_requested(ctx, window, presenter, session, tools, *open_request, loop);
    script.before_size(window, loop.frames);
    glfwGetFramebufferSize(window, &loop.fb_w, &loop.fb_h);
    script.simulate_minimized(loop.fb_w, loop.fb_h);
    if (loop.fb_w <= 0 || loop.fb_h <= 0 || glfwGetWindowAttrib(window, GLFW_ICONIFIED) == GLFW_TRUE) {
      glfwWaitEventsTimeout(0.05);  // minimized: nothing to draw
      continue;
    }
    const VkExtent2D fb{uint32_t(loop.fb_w), uint32_t(loop.fb_h)};
    if (!presenter.fit(fb)) continue;

    draw_panels(window, presenter, *session, tools, script, fb, screenshot, loop);
    renderer::Renderer& r = *session->renderer;
    OrbitCamera& camera = *session->camera;
    const bool moved = camera.take_changed();
    if (moved) r.set_camera(camera.camera());
    size_for_interaction(r, *session->ui, fb, moved, screenshot, script.interacting(), loop);
    r.render_frame();
    script.during_frame(window);
    if (!presenter.present(r.display_image(), tools.overlay(), fb)) continue;
    count_frame(ctx, *session->ui, loop);
    script.presented(loop.frames, fb, presenter.extent());
    if (const auto stop = script.failed(tools)) {
      presenter.wait();
      return stop;
    }
    if (screenshot && loop.frames >= a.frames && !script.waiting(loop.frames, *session->ui, tools)) break;
  }
  return std::nullopt;
}

int run(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options) {
  Glfw glfw;
  if (!glfw.ok) return no_display();
  if (glfwVulkanSupported() != GLFW_TRUE) {
    std::cerr << "sss-viewer: error: GLFW finds no Vulkan loader for windows\n";
    return kExitRuntime;
  }
  WindowHandle win;
  win.window = open_window(a, window_title(scene, a.scene));
  if (win.window == nullptr) return no_display();
  GLFWwindow* window = win.window;
  vk::Context ctx(window_context_options(a, window));

  LoopState loop;
  glfwGetFramebufferSize(window, &loop.fb_w, &loop.fb_h);
  if (loop.fb_w > 0 && loop.fb_h > 0) {
    options.width = static_cast<uint32_t>(loop.fb_w);
    options.height = static_cast<uint32_t>(loop.fb_h);
  }
  std::unique_ptr<Session> session = make_session(ctx, scene, a.scene, options);
  session->ui->set_interactive_scale(a.interactive_scale);
  print_warnings(*session->renderer);
  glfwSetDropCallback(window, [](GLFWwindow*, int count, const char** paths) {
    for (int i = 0; i < count; ++i) dropped_files().emplace_back(paths[i]);
  });

  Presenter presenter(ctx, {uint32_t(std::max(loop.fb_w, 0)), uint32_t(std::max(loop.fb_h, 0))}, a.vsync == "on");
  ImGuiSession imgui;
  imgui.glfw = ImGui_ImplGlfw_InitForVulkan(window, true);
  imgui.vulkan = presenter.init_imgui();

  ViewerTools tools(ctx);
  ScriptedDriver script(a);
  if (!script.start(*session->ui)) return kExitUsage;
  // A failure inside a frame (a device allocation, a lost device) unwinds through the
  // objects above, which the frame in flight may still use: wait for the device first.
  std::optional<int> stopped;
  try {
    stopped = viewer_loop(a, ctx, window, presenter, session, tools, script, loop);
  } catch (...) {
    ctx.wait_idle();
    throw;
  }
  if (stopped) return *stopped;
  presenter.wait();
  ctx.wait_idle();
  if (!a.screenshot.empty()) {
    if (auto refused = refuse_input_overwrite(a.screenshot, session->inputs)) {
      std::cerr << "sss-viewer: error: --screenshot: " << *refused << '\n';
      return kExitUsage;
    }
    write_frame(*session->renderer, a.screenshot);
  }
  if (a.stats) print_window_stats(ctx, presenter, *session, tools, loop);
  return kExitOk;
}

}  // namespace

int run_window(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options) {
  if (!has_display()) return no_display();
  return run(a, scene, options);
}

}  // namespace sss::app
