#include "Window.h"

#include "ExitCodes.h"
#include "CliSupport.h"
#include "FrameOutput.h"
#include "InputFiles.h"
#include "OrbitCamera.h"
#include "Tools.h"
#include "Ui.h"

#include "renderer/Renderer.h"
#include "renderer/image/Image.h"
#include "renderer/scene/BuiltinScenes.h"
#include "renderer/vk/Barrier.h"
#include "renderer/vk/Check.h"
#include "renderer/vk/Commands.h"
#include "renderer/vk/Context.h"
#include "renderer/vk/Image.h"
#include "renderer/vk/Swapchain.h"

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

using RenderPassHandle = vk::Handle<VkRenderPass, vkDestroyRenderPass>;
using FramebufferHandle = vk::Handle<VkFramebuffer, vkDestroyFramebuffer>;

// The blit stage: where the frame waits for the acquired image and writes it first.
constexpr vk::Scope kBlitWrite{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
constexpr vk::Scope kBlitRead{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
constexpr vk::Scope kBlitWait{VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE};
constexpr vk::Scope kColorAttachment{
    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
    VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};

bool has_display() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x != nullptr && *x != '\0') || (w != nullptr && *w != '\0');
}

int no_display() {
  std::cerr << "sss-viewer: error: " << kNoDisplayMessage << '\n';
  return kExitRuntime;
}

void check_imgui_vk(VkResult r) {
  if (r < 0) throw vk::VulkanError(r, "Dear ImGui's Vulkan backend");
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

// The UI pass over the blitted image: LOAD, COLOR_ATTACHMENT_OPTIMAL -> PRESENT_SRC.
RenderPassHandle create_ui_render_pass(const vk::Context& ctx, VkFormat format) {
  VkAttachmentDescription color{};
  color.format = format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkSubpassDependency deps[2]{};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  deps[1].dstStageMask = VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  deps[1].dstAccessMask = 0;
  VkRenderPassCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  info.attachmentCount = 1;
  info.pAttachments = &color;
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = deps;
  VkRenderPass pass = VK_NULL_HANDLE;
  VK_CHECK(vkCreateRenderPass(ctx.device(), &info, nullptr, &pass));
  return RenderPassHandle(ctx.device(), pass);
}

std::vector<FramebufferHandle> create_framebuffers(const vk::Context& ctx, VkRenderPass pass,
                                                   const vk::Swapchain& sc) {
  std::vector<FramebufferHandle> out;
  for (uint32_t i = 0; i < sc.image_count(); ++i) {
    VkImageView view = sc.view(i);
    VkFramebufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    info.renderPass = pass;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = sc.extent().width;
    info.height = sc.extent().height;
    info.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(ctx.device(), &info, nullptr, &fb));
    out.emplace_back(ctx.device(), fb);
  }
  return out;
}

vk::DescriptorPoolHandle create_imgui_pool(const vk::Context& ctx) {
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  info.maxSets = 16;
  info.poolSizeCount = 1;
  info.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateDescriptorPool(ctx.device(), &info, nullptr, &pool));
  return vk::DescriptorPoolHandle(ctx.device(), pool);
}

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

int run(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options) {
  Glfw glfw;
  if (!glfw.ok) return no_display();
  if (glfwVulkanSupported() != GLFW_TRUE) {
    std::cerr << "sss-viewer: error: GLFW finds no Vulkan loader for windows\n";
    return kExitRuntime;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  const std::string title = window_title(scene, a.scene);
  WindowHandle win;
  // A window larger than the screen opens smaller (its frame follows the framebuffer);
  // --screenshot keeps the size asked for, which is the saved image's.
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
  win.window = glfwCreateWindow(open_size.width, open_size.height, title.c_str(), nullptr, nullptr);
  if (win.window == nullptr) return no_display();
  GLFWwindow* window = win.window;

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
  vk::Context ctx(co);

  int fb_w = 0, fb_h = 0;
  glfwGetFramebufferSize(window, &fb_w, &fb_h);
  if (fb_w > 0 && fb_h > 0) {
    options.width = static_cast<uint32_t>(fb_w);
    options.height = static_cast<uint32_t>(fb_h);
  }
  std::unique_ptr<Session> session = make_session(ctx, scene, a.scene, options);
  session->ui->set_interactive_scale(a.interactive_scale);
  print_warnings(*session->renderer);
  glfwSetDropCallback(window, [](GLFWwindow*, int count, const char** paths) {
    for (int i = 0; i < count; ++i) dropped_files().emplace_back(paths[i]);
  });

  vk::Swapchain sc(ctx, {uint32_t(std::max(fb_w, 0)), uint32_t(std::max(fb_h, 0))}, a.vsync == "on");
  VkExtent2D swap_for{uint32_t(std::max(fb_w, 0)), uint32_t(std::max(fb_h, 0))};
  RenderPassHandle ui_pass = create_ui_render_pass(ctx, sc.format());
  std::vector<FramebufferHandle> framebuffers = create_framebuffers(ctx, ui_pass.get(), sc);
  vk::DescriptorPoolHandle imgui_pool = create_imgui_pool(ctx);
  // One buffer in its own pool, reset as a pool each frame (best practices: cheaper than
  // per-buffer resets, which need VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT).
  vk::CommandPoolHandle pool = vk::create_command_pool(ctx, 0);
  VkCommandBuffer cmd = vk::allocate_command_buffer(ctx, pool.get());
  vk::FenceHandle fence = vk::create_fence(ctx, true);
  vk::SemaphoreHandle acquired = vk::create_semaphore(ctx);
  std::vector<vk::SemaphoreHandle> rendered;  // one per swapchain image
  auto make_rendered = [&] {
    while (rendered.size() < sc.image_count()) rendered.push_back(vk::create_semaphore(ctx));
  };
  make_rendered();

  ImGuiSession imgui;
  imgui.glfw = ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = ctx.instance();
  init.PhysicalDevice = ctx.physical_device();
  init.Device = ctx.device();
  init.QueueFamily = ctx.queue_family();
  init.Queue = ctx.queue();
  init.DescriptorPool = imgui_pool.get();
  init.MinImageCount = std::max(sc.min_image_count(), 2u);
  init.ImageCount = std::max(sc.image_count(), init.MinImageCount);
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.CheckVkResultFn = check_imgui_vk;
  imgui.vulkan = ImGui_ImplVulkan_Init(&init, ui_pass.get());
  vk::submit_once(ctx, [](VkCommandBuffer c) { ImGui_ImplVulkan_CreateFontsTexture(c); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();

  ViewerTools tools(ctx);
  if (!a.test_edit.empty() && !session->ui->script_edit(a.test_edit)) {
    std::cerr << "sss-viewer: error: --test-edit: expected preset=NAME, model=NAME or layers=FILE.json, got '"
              << a.test_edit << "'\n";
    return kExitUsage;
  }
  bool r_was_down = false;

  auto recreate_swapchain = [&](VkExtent2D size) {
    vk::wait_for_fence(ctx, fence.get());  // the last frame's UI pass uses the framebuffers
    framebuffers.clear();
    sc.recreate(size);
    swap_for = size;
    if (!sc.valid()) return;
    framebuffers = create_framebuffers(ctx, ui_pass.get(), sc);
    make_rendered();
    ImGui_ImplVulkan_SetMinImageCount(std::max(sc.min_image_count(), 2u));
  };

  const bool screenshot = !a.screenshot.empty();
  int frames = 0;
  int simulated_minimized = 0;  // --test-resize: frames reported as 0x0
  double frame_ms = 0.0, timed_ms = 0.0;
  int timed_frames = 0;
  std::optional<std::string> open_request_ui;  // from the Tools window, for the next frame
  bool test_opened = false;
  // --test-resize-storm: the sizes, in order; three per loop iteration.
  static constexpr int kStorm[10][2] = {{1, 1},   {2000, 1200}, {37, 611},  {640, 360}, {2, 3},
                                        {1280, 720}, {321, 177}, {1, 400}, {900, 1}, {160, 90}};
  constexpr int kStormChanges = 50;
  int storm_next = 0;          // changes made so far
  int frames_after_storm = 0;  // frames presented at the final size after the storm
  std::uint64_t allocations_at_first_frame = 0;  // device-memory allocations (--stats)
  const auto storm_resize = [&] {
    if (storm_next >= kStormChanges) return;
    const int* size = kStorm[storm_next % 10];
    glfwSetWindowSize(window, size[0], size[1]);
    if (++storm_next == kStormChanges) glfwSetWindowSize(window, a.width, a.height);
  };
  auto last_interaction = std::chrono::steady_clock::time_point{};
  auto last = std::chrono::steady_clock::now();
  // A failure inside a frame (a device allocation, a lost device) unwinds through the
  // objects below, which the frame in flight may still use: wait for the device first.
  try {
  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    std::optional<std::string> open_request = std::move(open_request_ui);
    open_request_ui.reset();
    if (!dropped_files().empty()) {
      open_request = dropped_files().back();  // several at once: the last one
      dropped_files().clear();
    }
    if (!a.test_open.empty() && frames == 2 && !test_opened) {  // tests: as if dropped
      open_request = a.test_open;
      test_opened = true;
    }
    if (open_request) {
      // The frame in flight reads the old renderer's display image: wait for it first.
      vk::wait_for_fence(ctx, fence.get());
      std::string message;
      renderer::RenderOptions next_options = session->renderer->options();
      next_options.width = uint32_t(std::max(fb_w, 1));  // full size, whatever was drawn last
      next_options.height = uint32_t(std::max(fb_h, 1));
      auto next = open_scene(ctx, *open_request, next_options, session->scene.environment, message);
      const bool failed = next == nullptr;  // the scene shown stays
      if (next) {
        next->ui->set_interactive_scale(session->ui->interactive_scale());
        tools.reset();
        session = std::move(next);  // the old renderer goes here, its frame finished
        glfwSetWindowTitle(window, window_title(session->scene, session->source).c_str());
      }
      std::cerr << "sss-viewer: " << (failed ? "error: " : "") << message << '\n';
      tools.set_message(message, failed);
    }
    renderer::Renderer& r = *session->renderer;
    OrbitCamera& camera = *session->camera;
    ViewerUi& ui = *session->ui;
    if (a.test_resize) {
      // Exercise resize and minimize between frames (Xvfb has no window manager, so
      // iconify may do nothing there: 0x0 is also simulated for two iterations).
      if (frames == 1) glfwSetWindowSize(window, a.width + 64, a.height + 36);
      if (frames == 2 && simulated_minimized == 0) {
        glfwIconifyWindow(window);
        simulated_minimized = 3;
      }
      if (frames == 3) glfwRestoreWindow(window);
      if (frames == 4) glfwSetWindowSize(window, a.width, a.height);
    }
    if (a.test_resize_storm) {  // two changes before this frame's size is read
      storm_resize();
      storm_resize();
    }
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    if (simulated_minimized > 1) {
      --simulated_minimized;
      fb_w = fb_h = 0;
    }
    if (fb_w <= 0 || fb_h <= 0 || glfwGetWindowAttrib(window, GLFW_ICONIFIED) == GLFW_TRUE) {
      glfwWaitEventsTimeout(0.05);  // minimized: nothing to draw
      continue;
    }
    const VkExtent2D fb{uint32_t(fb_w), uint32_t(fb_h)};
    if (!sc.valid() || fb.width != swap_for.width || fb.height != swap_for.height) {
      recreate_swapchain(fb);
      if (!sc.valid()) continue;
    }

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    drive_camera(window, camera, r_was_down, float(fb.width), float(fb.height));
    // One frame in flight: the previous blit and UI pass finish before the panels may
    // change (or read back) the renderer's resources.
    vk::wait_for_fence(ctx, fence.get());
    ui.draw(r, frame_ms);
    if (!session->framed) {
      // The first frame of a scene: with the panel open, the subject moves into the part
      // of the window it leaves free. --screenshot keeps the scene's camera, so that it
      // stays the headless frame.
      session->framed = true;
      if (!screenshot) camera.frame_free_area(ui.panel_right(), float(fb.width), float(fb.height));
    }
    LiveState live{&session->scene, session->source, ui.editor().applied(), ui.lights(),
                   fb.width, fb.height, &session->inputs};
    if (!a.test_compare.empty() && frames == 2 && !tools.reference_running() && !tools.metrics()) {
      tools.start_reference(r, live);
      tools.set_view(a.test_compare == "split" ? 1 : a.test_compare == "reference" ? 2 : 3, 0.5f);
      if (a.test_compare == "log-ratio") tools.set_error_map(ViewerTools::ErrorMap::LogRatio);
    }
    if (std::optional<std::string> path = tools.draw(r, live)) open_request_ui = *path;
    ImGui::Render();
    const bool moved = camera.take_changed();
    if (moved) r.set_camera(camera.camera());

    // Interactive resolution: while the view moves or a widget is dragged, render at
    // ui.interactive_scale() of the window and let the blit upscale; the full-size frame
    // comes back 0.3 s after the last change. --screenshot frames are always full size
    // (unless --test-interaction, which times the scaled frames).
    const auto now_steady = std::chrono::steady_clock::now();
    if ((!screenshot && (moved || ImGui::IsAnyItemActive())) || a.test_interaction)
      last_interaction = now_steady;
    const float scale = ui.interactive_scale();
    const bool scaled = scale < 1.0f && now_steady - last_interaction < std::chrono::milliseconds(300);
    const VkExtent2D render_size =
        scaled ? VkExtent2D{std::max(1u, uint32_t(std::lround(float(fb.width) * scale))),
                            std::max(1u, uint32_t(std::lround(float(fb.height) * scale)))}
               : fb;
    if (render_size.width != r.options().width || render_size.height != r.options().height)
      r.resize(render_size.width, render_size.height);

    r.render_frame();
    if (a.test_resize_storm) storm_resize();  // and one while the frame is under way
    uint32_t index = 0;
    if (!sc.acquire(acquired.get(), index)) {
      recreate_swapchain(fb);
      continue;
    }
    VkFence frame_fence = fence.get();
    VK_CHECK(vkResetFences(ctx.device(), 1, &frame_fence));
    VK_CHECK(vkResetCommandPool(ctx.device(), pool.get(), 0));
    VkCommandBufferBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    ctx.begin_label(cmd, "present");
    const vk::Image& display = r.display_image();
    const VkImageSubresourceRange color_range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImage target = sc.image(index);
    vk::pipeline_barrier(
        cmd, {vk::image_barrier(display, renderer::Renderer::display_layout(),
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, vk::kComputeWrite, kBlitRead),
              vk::image_barrier(target, color_range, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kBlitWait, kBlitWrite)});
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(display.width()), int32_t(display.height()), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[1] = {int32_t(sc.extent().width), int32_t(sc.extent().height), 1};
    const bool same = display.width() == sc.extent().width && display.height() == sc.extent().height;
    vkCmdBlitImage(cmd, display.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   same ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
    if (const auto overlay = tools.overlay()) {
      // The compare view: the reference or the heat map over the columns left of the
      // split (both stay in TRANSFER_SRC_OPTIMAL from their upload).
      const vk::Image& over = *overlay->image;
      const int32_t src_w = int32_t(std::lround(overlay->split * float(over.width())));
      const int32_t dst_w = int32_t(std::lround(overlay->split * float(sc.extent().width)));
      if (src_w > 0 && dst_w > 0) {
        vk::pipeline_barrier(cmd, {vk::image_barrier(target, color_range,
                                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                                     kBlitWrite, kBlitWrite)});
        VkImageBlit part = blit;
        part.srcOffsets[1] = {src_w, int32_t(over.height()), 1};
        part.dstOffsets[1] = {dst_w, int32_t(sc.extent().height), 1};
        vkCmdBlitImage(cmd, over.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &part,
                       same ? VK_FILTER_NEAREST : VK_FILTER_LINEAR);
      }
    }
    vk::pipeline_barrier(
        cmd, {vk::image_barrier(display, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                renderer::Renderer::display_layout(), kBlitRead, vk::kAllCommands),
              vk::image_barrier(target, color_range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kBlitWrite,
                                kColorAttachment)});
    VkRenderPassBeginInfo rp{};
    rp.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    rp.renderPass = ui_pass.get();
    rp.framebuffer = framebuffers[index].get();
    rp.renderArea = {{0, 0}, sc.extent()};
    vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vkCmdEndRenderPass(cmd);
    ctx.end_label(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkSemaphoreSubmitInfo wait{};
    wait.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
    wait.semaphore = acquired.get();
    wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    VkSemaphoreSubmitInfo signal{};
    signal.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO;
    signal.semaphore = rendered[index].get();
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cb{};
    cb.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO;
    cb.commandBuffer = cmd;
    VkSubmitInfo2 submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cb;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    ctx.submit({&submit, 1}, fence.get());
    if (!sc.present(index, rendered[index].get())) recreate_swapchain(fb);

    ++frames;
    if (frames == 2 && a.test_host_oom == "frame") throw std::bad_alloc();
    if (frames == 1) allocations_at_first_frame = ctx.successful_allocations();
    if (a.test_resize_storm && storm_next >= kStormChanges && fb_w == a.width && fb_h == a.height &&
        sc.extent().width == fb.width && sc.extent().height == fb.height)
      ++frames_after_storm;
    const auto now = std::chrono::steady_clock::now();
    frame_ms = std::chrono::duration<double, std::milli>(now - last).count();
    last = now;
    ui.frame_presented(frame_ms);
    if (frames > 1) {  // the first frame includes start-up
      timed_ms += frame_ms;
      ++timed_frames;
    }
    if (!a.test_compare.empty() && !tools.compare_error().empty()) {
      std::cerr << "sss-viewer: error: compare: " << tools.compare_error() << '\n';
      vk::wait_for_fence(ctx, fence.get());
      return kExitRuntime;
    }
    const bool waiting = (!a.test_edit.empty() && ui.busy()) ||
                         (!a.test_compare.empty() && (frames <= 2 || !tools.metrics()));
    const bool storming = a.test_resize_storm && frames_after_storm < a.frames;
    if (screenshot && frames >= a.frames && !waiting && !storming) break;
  }
  } catch (...) {
    ctx.wait_idle();
    throw;
  }
  vk::wait_for_fence(ctx, fence.get());
  ctx.wait_idle();
  const renderer::Renderer& r = *session->renderer;
  const ViewerUi& ui = *session->ui;

  if (screenshot) {
    if (auto refused = refuse_input_overwrite(a.screenshot, session->inputs)) {
      std::cerr << "sss-viewer: error: --screenshot: " << *refused << '\n';
      return kExitUsage;
    }
    write_frame(r, a.screenshot);
  }
  if (a.stats) {
    std::printf("window %dx%d (rendered %ux%u), sss %s, mode %s, present %s, %d frame(s)\n",
                fb_w, fb_h, r.options().width, r.options().height, std::string(renderer::sss_mode_name(r.options().sss)).c_str(),
                std::string(renderer::sss_kind_name(r.options().kind)).c_str(),
                sc.present_mode() == VK_PRESENT_MODE_FIFO_KHR        ? "fifo"
                : sc.present_mode() == VK_PRESENT_MODE_MAILBOX_KHR ? "mailbox"
                                                                    : "immediate",
                frames);
    print_pass_times(r.stats());
    if (timed_frames > 0) {
      std::printf("%-16s %10.3f\n", "window frame", timed_ms / timed_frames);
      std::printf("%-16s %10.1f\n", "fps", 1000.0 * timed_frames / timed_ms);
    }
    ui.print_stats(stdout);
    std::printf("%-16s %10llu\n", "allocations", static_cast<unsigned long long>(ctx.successful_allocations()));
    std::printf("%-16s %10llu\n", "allocations @1", static_cast<unsigned long long>(allocations_at_first_frame));
    if (const auto& m = tools.metrics())
      std::printf("compare: relative RMSE %.6f, PSNR %.2f dB, SSIM %.4f, max abs %.4f\n",
                  m->relative_rmse, m->psnr_db, m->ssim, m->max_abs_error);
  }
  return kExitOk;
}

}  // namespace

int run_window(const ViewerArgs& a, const scene::Scene& scene, renderer::RenderOptions options) {
  if (!has_display()) return no_display();
  return run(a, scene, options);
}

}  // namespace sss::app
