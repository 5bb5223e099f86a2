#include "Tools.h"

#include "CliSupport.h"
#include "InputFiles.h"

#include "renderer/FrameTargets.h"
#include "renderer/Renderer.h"
#include "renderer/image/AtomicFile.h"
#include "renderer/image/HeatMap.h"
#include "renderer/scene/GltfExport.h"
#include "renderer/scene/SssExtras.h"
#include "renderer/vk/Transfer.h"
#include "profiles/KernelExport.h"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>

namespace sss::app {

namespace {

const ImVec4 kRed(1.0f, 0.4f, 0.4f, 1.0f);
const ImVec4 kYellow(1.0f, 0.85f, 0.3f, 1.0f);

void copy_to(char* dst, std::size_t size, const std::string& s) {
  std::snprintf(dst, size, "%s", s.c_str());
}

bool exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

bool is_builtin(const std::string& source) { return source.rfind("builtin:", 0) == 0; }

std::string file_stem(const std::string& source) {
  if (is_builtin(source)) return source.substr(8);
  return std::filesystem::path(source).stem().string();
}

// A C identifier for the header's prefix.
std::string c_identifier(std::string name) {
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) c = '_';
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name.insert(0, "k_");
  return name;
}

std::string sanitized(std::string name) {
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) c = '_';
  return name.empty() ? std::string("material") : name;
}

// "skin (preset skin1, mc-table, scale 1)": what the kernel files record.
std::string describe(const scene::Material& m) {
  std::ostringstream out;
  out << "material '" << m.name << "': ";
  if (const auto* p = std::get_if<scene::PresetSource>(&m.sss.source))
    out << "preset " << p->name;
  else if (std::holds_alternative<scene::CoefficientSource>(m.sss.source))
    out << "coefficients";
  else
    out << "artist colour + mfp";
  const profiles::Medium e = m.sss.effective_medium();
  out << ", scale " << m.sss.scale << "; effective sigma_a [" << e.sigma_a[0] << ", "
      << e.sigma_a[1] << ", " << e.sigma_a[2] << "] sigma_s [" << e.sigma_s[0] << ", "
      << e.sigma_s[1] << ", " << e.sigma_s[2] << "] /mm";
  return out.str();
}

}  // namespace

// ---- ReferenceJob ----------------------------------------------------------------

void ReferenceJob::start(scene::Scene scene, const reference::ReferenceOptions& options) {
  cancel();
  {
    std::lock_guard lock(mutex_);
    stage_ = "starting";
    fraction_ = 0.0;
    result_.reset();
    error_.clear();
  }
  cancel_ = false;
  running_ = true;
  worker_ = std::thread([this, s = std::move(scene), options] {
    try {
      reference::ReferenceImage img = reference::render_reference(
          s, options,
          [this](const char* stage, double f) {
            std::lock_guard lock(mutex_);
            stage_ = stage;
            fraction_ = f;
          },
          &cancel_);
      std::lock_guard lock(mutex_);
      result_ = std::move(img);
    } catch (const reference::Cancelled&) {
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = e.what();
    }
    running_ = false;
  });
}

void ReferenceJob::cancel() {
  cancel_ = true;
  if (worker_.joinable()) worker_.join();
  running_ = false;
}

std::string ReferenceJob::progress() const {
  std::lock_guard lock(mutex_);
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s %.0f%%", stage_.c_str(), 100.0 * fraction_);
  return buf;
}

double ReferenceJob::fraction() const {
  std::lock_guard lock(mutex_);
  return fraction_;
}

std::optional<reference::ReferenceImage> ReferenceJob::take() {
  std::lock_guard lock(mutex_);
  if (!result_) return std::nullopt;
  std::optional<reference::ReferenceImage> out = std::move(result_);
  result_.reset();
  return out;
}

std::string ReferenceJob::take_error() {
  std::lock_guard lock(mutex_);
  std::string e = std::move(error_);
  error_.clear();
  return e;
}

// ---- ViewerTools -----------------------------------------------------------------

std::string live_key(const renderer::Renderer& r, const LiveState& live) {
  nlohmann::json k;
  const scene::Camera& c = r.camera();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) k["camera"].push_back(c.world[i][j]);
  k["lens"] = {int(c.projection), c.yfov, c.xmag, c.znear, c.zfar};
  k["size"] = {live.width, live.height, r.options().exposure};
  for (const scene::Material& m : live.materials)
    k["materials"].push_back(m.sss.enabled ? scene::sss_extras_json(m.sss) : nlohmann::json());
  for (const scene::Light& l : live.lights) {
    nlohmann::json lj = {l.intensity, l.color.x, l.color.y, l.color.z};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) lj.push_back(l.world[i][j]);
    k["lights"].push_back(lj);
  }
  return k.dump();
}

void ViewerTools::reset() {
  job_.cancel();
  (void)job_.take();
  (void)job_.take_error();
  reference_.reset();
  metrics_.reset();
  compare_pending_ = false;
  reference_image_ = {};
  heat_image_ = {};
  view_ = 0;
  compare_error_.clear();
  export_message_.clear();
}

std::optional<ViewerTools::Overlay> ViewerTools::overlay() const {
  if (view_ == 0 || !reference_image_) return std::nullopt;
  if (view_ == 3) return heat_image_ ? std::optional(Overlay{&heat_image_, 1.0f}) : std::nullopt;
  return Overlay{&reference_image_, view_ == 1 ? split_ : 1.0f};
}

vk::Image ViewerTools::upload(const image::Image& img, const char* name) const {
  vk::Image out(context_, vk::ImageDesc(uint32_t(img.width), uint32_t(img.height),
                                        renderer::kDisplayFormat,
                                        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                            VK_IMAGE_USAGE_SAMPLED_BIT,  // vk::Image makes a view
                                        name));
  std::vector<std::uint8_t> texels(img.rgba.size());
  for (std::size_t i = 0; i < texels.size(); ++i)
    texels[i] = static_cast<std::uint8_t>(std::lround(std::clamp(img.rgba[i], 0.0f, 1.0f) * 255.0f));
  vk::upload_image(context_, out, std::as_bytes(std::span(texels)),
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  return out;
}

std::optional<std::string> ViewerTools::draw(renderer::Renderer& r, const LiveState& live) {
  open_request_.reset();
  if (live.source != last_source_) {  // a new scene: new default export names
    last_source_ = live.source;
    const std::string stem = file_stem(live.source);
    copy_to(gltf_path_, sizeof gltf_path_,
            is_builtin(live.source) ? scene::unused_path(stem + "-sss.json")
                                    : scene::default_export_path(live.source));
    kernel_path_[0] = '\0';
    kernel_material_ = 0;
  }
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x - 8.0f, 8.0f), ImGuiCond_FirstUseEver, ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(310, 0), ImVec2(310, std::max(size.y - 16.0f, 50.0f)));
  const bool expand = expand_ || show_open_;
  ImGui::SetNextWindowCollapsed(!expand, expand ? ImGuiCond_Always : ImGuiCond_FirstUseEver);
  poll_reference(r, live);  // also while the window is collapsed
  if (ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    draw_open();
    draw_compare(r, live);
    draw_export(r, live);
  }
  ImGui::End();
  return open_request_;
}

void ViewerTools::draw_open() {
  if (show_open_) ImGui::SetNextItemOpen(true);
  show_open_ = false;
  if (!ImGui::CollapsingHeader("Open", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextWrapped("A .gltf/.glb path or builtin:NAME, or drop a file on the window.");
  const bool enter = ImGui::InputText("##path", open_path_, sizeof open_path_,
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Open") || enter) && open_path_[0] != '\0') open_request_ = open_path_;
  if (message_.empty()) return;
  if (message_error_) ImGui::PushStyleColor(ImGuiCol_Text, kRed);
  ImGui::TextWrapped("%s", message_.c_str());
  if (message_error_) ImGui::PopStyleColor();
}

void ViewerTools::compare_now(renderer::Renderer& r) {
  compare_error_.clear();
  metrics_.reset();
  try {
    const image::Image live = r.read_display();
    const image::Image& ref = reference_->display;
    if (live.width != ref.width || live.height != ref.height) {
      compare_error_ = "the window was resized since the reference: render it again";
      return;
    }
    metrics_ = image::compare(live, ref);
    errors_ = image::pixel_errors(live, ref);
    mask_ = image::geometry_mask(live, ref);
    // The top of the scale: the 99th percentile of the compared pixels' errors, so that a
    // few silhouette or shadow-edge pixels do not turn the rest of the map dark.
    std::vector<float> compared;
    for (std::size_t i = 0; i < errors_.size(); ++i)
      if (mask_[i] != 0) compared.push_back(errors_[i]);
    heat_max_ = 1.0;
    if (!compared.empty()) {
      const auto nth = compared.begin() + std::ptrdiff_t(0.99 * double(compared.size() - 1));
      std::nth_element(compared.begin(), nth, compared.end());
      heat_max_ = std::max(double(*nth), 1e-3);
    }
    render_heat(live.width, live.height);
  } catch (const std::exception& e) {
    compare_error_ = e.what();
  }
}

void ViewerTools::render_heat(int width, int height) {
  try {
    const image::Image canvas = image::render_heatmap(errors_, mask_, width, height, heat_max_);
    image::Image heat(width, height);  // the error image, without the colour bar
    for (int y = 0; y < height; ++y)
      std::copy_n(canvas.pixel(0, y), 4 * std::size_t(width), heat.pixel(0, y));
    for (std::size_t i = 3; i < heat.rgba.size(); i += 4) heat.rgba[i] = 1.0f;
    heat_image_ = upload(heat, "compare heat map");
  } catch (const std::exception& e) {
    compare_error_ = e.what();
  }
}

void ViewerTools::start_reference(const renderer::Renderer& r, const LiveState& live) {
  scene::Scene s = *live.scene;
  s.materials = live.materials;
  s.lights = live.lights;
  s.cameras = {r.camera()};
  reference::ReferenceOptions o;
  o.width = live.width > 0 ? live.width : r.options().width;
  o.height = live.height > 0 ? live.height : r.options().height;
  o.exposure = r.options().exposure;
  o.spacing_mfp = spacing_mfp_;
  o.max_solid_angle = error_bound_;
  // Leave a core to the window when there are few.
  o.threads = int(std::max(2u, std::thread::hardware_concurrency()) - 1);
  job_key_ = live_key(r, live);
  compare_error_.clear();
  job_.start(std::move(s), o);
}

void ViewerTools::poll_reference(renderer::Renderer& r, const LiveState& live) {
  if (std::optional<reference::ReferenceImage> done = job_.take()) {
    reference_ = std::move(done);
    reference_key_ = job_key_;
    // 8-bit codes, as shown and as sss-reference writes its PNG: the metrics are then
    // those of `sss-compare live.png reference.png`.
    for (float& v : reference_->display.rgba) v = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
    try {
      reference_image_ = upload(reference_->display, "compare reference");
    } catch (const std::exception& e) {
      compare_error_ = e.what();
    }
    compare_pending_ = live_key(r, live) == reference_key_;
    if (view_ == 0) view_ = 1;
  }
  // Compare the full-size frame (not a scaled one drawn while the view moves).
  if (compare_pending_ && reference_ && r.options().width == std::uint32_t(reference_->display.width) &&
      r.options().height == std::uint32_t(reference_->display.height)) {
    compare_pending_ = false;
    compare_now(r);
  }
  if (std::string e = job_.take_error(); !e.empty()) compare_error_ = "reference: " + e;
}

void ViewerTools::draw_compare(renderer::Renderer& r, const LiveState& live) {
  if (expand_) ImGui::SetNextItemOpen(true);
  expand_ = false;
  if (!ImGui::CollapsingHeader("Compare with the CPU reference")) return;

  ImGui::SliderFloat("spacing (mfp)", &spacing_mfp_, 0.25f, 2.0f, "%.2f");
  ImGui::SliderFloat("error bound (sr)", &error_bound_, 0.05f, 1.0f, "%.2f");
  if (job_.running()) {
    ImGui::ProgressBar(float(job_.fraction()), ImVec2(-1, 0), job_.progress().c_str());
    if (ImGui::Button("Cancel")) job_.cancel();
  } else if (ImGui::Button("Render reference of this view")) {
    start_reference(r, live);
  }
  if (!compare_error_.empty()) ImGui::TextColored(kRed, "%s", compare_error_.c_str());
  if (!reference_) return;

  const reference::ReferenceStats& st = reference_->stats;
  ImGui::Text("reference: %zu points, %.1f s", st.points, st.total_ms / 1000.0);
  const bool stale = live_key(r, live) != reference_key_;
  if (stale) ImGui::TextColored(kYellow, "The view or a material changed since: render again.");
  ImGui::RadioButton("live", &view_, 0);
  ImGui::SameLine();
  ImGui::RadioButton("split", &view_, 1);
  ImGui::SameLine();
  ImGui::RadioButton("reference", &view_, 2);
  ImGui::SameLine();
  ImGui::RadioButton("error", &view_, 3);
  if (view_ == 1) {
    ImGui::SliderFloat("split", &split_, 0.0f, 1.0f, "%.2f");
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImDrawList* fg = ImGui::GetForegroundDrawList();
    fg->AddLine(ImVec2(split_ * size.x, 0.0f), ImVec2(split_ * size.x, size.y),
                IM_COL32(255, 255, 255, 200), 1.5f);
    fg->AddText(ImVec2(split_ * size.x - 76.0f, size.y - 22.0f), IM_COL32_WHITE, "reference");
    fg->AddText(ImVec2(split_ * size.x + 8.0f, size.y - 22.0f), IM_COL32_WHITE, "live");
    ImGui::TextDisabled("left: reference, right: live frame");
  }
  if (!stale && ImGui::Button("Compare the current frame")) compare_pending_ = true;
  if (!metrics_) return;
  const image::Metrics& m = *metrics_;
  ImGui::Text("relative RMSE %.2f%%   RMSE %.4f", 100.0 * m.relative_rmse, m.rmse);
  ImGui::Text("PSNR %.1f dB   SSIM %.4f", m.psnr_db, m.ssim);
  ImGui::Text("max |error| %.3f at (%d, %d)", m.max_abs_error, m.max_abs_x, m.max_abs_y);
  ImGui::Text("%.2f%% of %zu pixels over %.0f%% of peak", 100.0 * m.fraction_over_threshold,
              m.compared_pixels, 100.0 * m.threshold);
  if (view_ == 3) {  // the heat map's colour bar
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
    constexpr int kSteps = 32;
    for (int i = 0; i < kSteps; ++i) {
      const image::Rgb c = image::viridis((i + 0.5) / kSteps);
      dl->AddRectFilled(ImVec2(p.x + w * i / kSteps, p.y), ImVec2(p.x + w * (i + 1) / kSteps, p.y + h),
                        ImGui::GetColorU32(ImVec4(c[0], c[1], c[2], 1.0f)));
    }
    ImGui::Dummy(ImVec2(w, h));
    float top = float(heat_max_);
    if (ImGui::SliderFloat("top", &top, 1e-3f, 1.0f, "%.3f", ImGuiSliderFlags_Logarithmic) &&
        reference_) {
      heat_max_ = top;
      render_heat(reference_->display.width, reference_->display.height);
    }
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("|error| of the display codes, 0 to top (default: 99th percentile); "
                       "grey: no geometry in one image");
    ImGui::PopStyleColor();
  }
}

std::string write_new_file(const std::string& path, const std::string& bytes, bool replace,
                           const std::vector<std::filesystem::path>* inputs) {
  if (path.empty()) return "no file name given";
  if (inputs != nullptr)
    if (auto refused = refuse_input_overwrite(path, *inputs)) return *refused;
  if (!replace && exists(path))
    return path + " exists: tick 'replace existing files' or change the name";
  try {
    image::write_file_atomically(path, bytes);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "saved " + path;
}

std::string export_materials(const LiveState& live, const std::string& path, bool replace) {
  if (path.empty()) return "no file name given";
  if (is_builtin(live.source)) {
    nlohmann::ordered_json doc;
    doc["scene"] = live.source;
    doc["materials"] = nlohmann::ordered_json::array();
    for (const scene::Material& m : live.materials) {
      nlohmann::ordered_json entry = {{"name", m.name}};
      if (m.sss.enabled)
        entry["extras"]["sss"] = nlohmann::ordered_json::parse(scene::sss_extras_json(m.sss).dump());
      doc["materials"].push_back(entry);
    }
    return write_new_file(path, doc.dump(2) + "\n", replace, live.inputs);
  }
  if (live.inputs != nullptr)
    if (auto refused = refuse_input_overwrite(path, *live.inputs)) return *refused;
  auto bytes = scene::gltf_with_sss_materials(live.source, live.materials, path);
  if (auto* e = std::get_if<scene::LoadError>(&bytes)) return e->what();
  return write_new_file(path, std::get<std::string>(bytes), replace, live.inputs);
}

std::string export_kernel(const renderer::Renderer& r, const LiveState& live, std::size_t material,
                          const std::string& path, bool replace) {
  if (material >= live.materials.size() || material >= r.materials().profiles.size() ||
      !r.materials().profiles[material])
    return "material " + std::to_string(material) + " has no fitted SSS profile";
  const renderer::MaterialProfile& profile = *r.materials().profiles[material];
  const scene::Material& m = live.materials[material];
  const profiles::KernelInfo info{std::string(profiles::model_name(m.sss.model)), describe(m)};
  std::string bytes;
  try {
    if (lower_extension(path) == ".h")
      bytes = profiles::kernel_to_c_header(
          profile.fit, info, &profile.kernel,
          c_identifier(std::filesystem::path(path).stem().string()));
    else
      bytes = profiles::kernel_to_json(profile.fit, info, &profile.kernel);
  } catch (const std::exception& e) {
    return e.what();
  }
  return write_new_file(path, bytes, replace, live.inputs);
}

void ViewerTools::draw_export(const renderer::Renderer& r, const LiveState& live) {
  if (!ImGui::CollapsingHeader("Export")) return;
  const bool builtin = is_builtin(live.source);
  ImGui::TextWrapped(builtin ? "SSS blocks of every material (a built-in scene has no glTF)"
                             : "A copy of the glTF with every material's extras.sss");
  ImGui::InputText("##gltf", gltf_path_, sizeof gltf_path_);
  ImGui::SameLine();
  const bool save_gltf = ImGui::Button(builtin ? "Save JSON" : "Save glTF");

  std::vector<int> sss;
  for (std::size_t i = 0; i < live.materials.size(); ++i)
    if (live.materials[i].sss.enabled) sss.push_back(int(i));
  bool save_json = false, save_header = false;
  if (!sss.empty()) {
    kernel_material_ = std::clamp(kernel_material_, 0, int(sss.size()) - 1);
    const scene::Material& km = live.materials[std::size_t(sss[std::size_t(kernel_material_)])];
    if (ImGui::BeginCombo("kernel of", km.name.c_str())) {
      for (int k = 0; k < int(sss.size()); ++k)
        if (ImGui::Selectable(live.materials[std::size_t(sss[std::size_t(k)])].name.c_str(),
                              k == kernel_material_)) {
          kernel_material_ = k;
          kernel_path_[0] = '\0';
        }
      ImGui::EndCombo();
    }
    if (kernel_path_[0] == '\0')
      copy_to(kernel_path_, sizeof kernel_path_,
              scene::unused_path(sanitized(file_stem(live.source) + "-" + km.name) + "-kernel"));
    ImGui::InputText("##kernel", kernel_path_, sizeof kernel_path_);
    ImGui::TextDisabled("(.json and .h are added)");
    save_json = ImGui::Button("Save kernel JSON");
    ImGui::SameLine();
    save_header = ImGui::Button("Save C header");
  }
  ImGui::Checkbox("replace existing files", &replace_);

  if (save_gltf) {
    const std::string out = gltf_path_;
    export_message_ = export_materials(live, out, replace_);
    if (export_message_.rfind("saved ", 0) == 0)  // the next save gets a new name
      copy_to(gltf_path_, sizeof gltf_path_,
              builtin ? scene::unused_path(out) : scene::default_export_path(live.source));
  }
  if (save_json || save_header) {
    const std::size_t index = std::size_t(sss[std::size_t(kernel_material_)]);
    export_message_ = export_kernel(r, live, index,
                                    std::string(kernel_path_) + (save_json ? ".json" : ".h"), replace_);
  }
  if (!export_message_.empty()) ImGui::TextWrapped("%s", export_message_.c_str());
}

}  // namespace sss::app
