#include "Tools.h"


#include "CliSupport.h"
#include "InputFiles.h"
#include "PanelWindow.h"
#include "ToolsText.h"
#include "UiColors.h"

#include "renderer/FrameTargets.h"
#include "renderer/Renderer.h"
#include "image/Tonemap.h"
#include "scene/GltfExport.h"
#include "scene/SssExtras.h"
#include "renderer/vk/Transfer.h"

#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <variant>

namespace sss::app {

using namespace tools_text;

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
  for (auto& r : results_) r.reset();
  compare_pending_ = false;
  reference_image_ = {};
  heat_image_ = {};
  map_image_ = {};
  clear_truth();  // a truth is of one scene's view
  truth_message_.clear();
  truth_error_ = false;
  view_ = 0;
  compare_error_.clear();
  export_message_.clear();
}

// The two images of each pair, test first: both names below follow from them.
std::optional<ViewerTools::Overlay> ViewerTools::overlay() const {
  switch (view_) {
    case 1:
    case 2:
      if (reference_image_) return Overlay{&reference_image_, view_ == 1 ? split_ : 1.0f};
      break;
    case 3:
      if (heat_image_) return Overlay{&heat_image_, 1.0f};
      break;
    case 4:
      if (truth_image_) return Overlay{&truth_image_, 1.0f};
      break;
    default: break;
  }
  return std::nullopt;
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
  poll(r, live);  // also while the window is collapsed
  const bool shown = ImGui::Begin("Tools", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  open_on_title_click(shown);
  if (shown) {
    // Fields leave room on their right for the longest label of the window, which the
    // default (65% of the width for the field) cut to "spacing (m" and "error bound".
    ImGui::PushItemWidth(-(ImGui::CalcTextSize("error bound (sr)").x + ImGui::GetStyle().ItemInnerSpacing.x));
    draw_open();
    draw_compare(r, live);
    draw_export(r, live);
    ImGui::PopItemWidth();
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
  // "##file": the header above is "Open" too, and one ID for both made the header take the
  // button's click (the button never fired; Enter did). ViewerTools.OpenButton... clicks it.
  if ((ImGui::Button("Open##file") || enter) && open_path_[0] != '\0') open_request_ = open_path_;
  if (message_.empty()) return;
  if (message_error_) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextWrapped("%s", message_.c_str());
  if (message_error_) ImGui::PopStyleColor();
}

namespace {

// 8-bit codes, as shown and as sss-reference writes its PNG: metrics of display images
// are then those of sss-compare on the PNGs.
void quantize(image::Image& display) {
  for (float& v : display.rgba) v = std::round(std::clamp(v, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

bool has_exr_magic(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char magic[4] = {};
  f.read(reinterpret_cast<char*>(magic), 4);
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  return f && std::memcmp(magic, kExr, 4) == 0;
}

const std::string* attribute(const image::Image& img, const std::string& name) {
  for (const auto& [k, v] : img.attributes)
    if (k == name) return &v;
  return nullptr;
}

// One pair: display metrics as sss-compare gives them for the two PNGs, and the log
// ratio of the linear images.
ViewerTools::PairResult compare_pair(const image::Image& a_display, const image::Image& a_hdr,
                                     const image::Image& b_display, const image::Image& b_hdr) {
  ViewerTools::PairResult out;
  out.width = a_display.width;
  out.height = a_display.height;
  out.metrics = image::compare(a_display, b_display);
  out.errors = image::pixel_errors(a_display, b_display);
  out.mask = image::geometry_mask(a_display, b_display);
  out.log2_ratio = image::log2_luminance_ratio(a_hdr, b_hdr, image::Encoding::Linear);
  out.log_stats = image::log_ratio_stats(out.log2_ratio, out.mask);
  // The absolute map's top: the 99th percentile of the compared pixels' errors
  // (image::robust_scale), at least one 8-bit code's worth.
  out.heat_max = std::max(image::robust_scale(out.errors, out.mask), 1e-3);
  return out;
}

}  // namespace

ViewerTools::PairImages ViewerTools::pair_images(Pair pair, bool reference_current) const {
  PairImages im;
  if (pair != Pair::ReferenceVsTruth) {
    im.a_display = &frame_display_;
    im.a_hdr = &frame_hdr_;
  } else if (reference_) {
    im.a_display = &reference_->display;
    im.a_hdr = &reference_->hdr;
  }
  if (pair == Pair::FrameVsReference) {
    if (reference_current) {
      im.b_display = &reference_->display;
      im.b_hdr = &reference_->hdr;
    }
  } else if (truth_) {
    im.b_display = &truth_display_;
    im.b_hdr = &*truth_;
  }
  return im;
}

std::string ViewerTools::compare_one(Pair pair, const PairImages& im) {
  const image::Image &a = *im.a_display, &b = *im.b_display;
  if (a.width != b.width || a.height != b.height)
    return pair == Pair::FrameVsReference
               ? "the window was resized since the reference: render it again"
               : pair_name(pair) + ": the ground truth (" + truth_source_ + ") is " + size_text(b.width, b.height) +
                     ", the " + (pair == Pair::FrameVsTruth ? "frame" : "reference") + " is " +
                     size_text(a.width, a.height);
  try {
    results_[int(pair)] = compare_pair(a, *im.a_hdr, b, *im.b_hdr);
  } catch (const std::exception& e) {
    return pair_name(pair) + ": " + e.what();
  }
  return "";
}

void ViewerTools::compare_now(renderer::Renderer& r, const LiveState& live) {
  compare_error_.clear();
  metrics_.reset();
  for (auto& res : results_) res.reset();
  try {
    frame_display_ = r.read_display();
    frame_hdr_ = r.read_hdr();
    if (truth_) show_truth(r.options().exposure);  // the exposure may have changed
  } catch (const std::exception& e) {
    compare_error_ = e.what();
    return;
  }
  const bool reference_current = reference_ && live_key(r, live) == reference_key_;
  if (truth_) {  // a new comparison, a new verdict
    truth_message_ = truth_info_;
    truth_error_ = false;
  }
  for (int p = 0; p < kPairs; ++p) {
    const Pair pair = Pair(p);
    const PairImages im = pair_images(pair, reference_current);
    if (!im.a_display || !im.b_display) continue;
    const std::string error = compare_one(pair, im);
    if (error.empty()) continue;
    if (pair != Pair::FrameVsReference) {  // it uses the truth
      truth_message_ = error;
      truth_error_ = true;
    } else {
      compare_error_ = error;
    }
  }
  if (results_[0]) metrics_ = results_[0]->metrics;
  if (!results_[int(pair_)])  // the chosen pair is not there: the first one that is
    for (int p = 0; p < kPairs; ++p)
      if (results_[p]) {
        pair_ = Pair(p);
        break;
      }
  render_map();
}

void ViewerTools::show_truth(float exposure) {
  if (!truth_ || (exposure == truth_exposure_ && truth_image_)) return;
  truth_display_ = image::tonemap(*truth_, exposure);
  quantize(truth_display_);
  truth_image_ = upload(truth_display_, "compare ground truth");
  truth_exposure_ = exposure;
}

bool ViewerTools::load_truth(const std::string& path, const renderer::Renderer& r,
                             const LiveState& live) {
  truth_warning_.clear();
  truth_error_ = true;
  const auto fail = [&](std::string message) {
    truth_message_ = std::move(message) + (truth_ ? " (not loaded; the previous truth stays)" : "");
    return false;
  };
  if (path.empty()) return fail("ground truth: no file name given");
  auto read = image::read_image(path);
  if (auto* e = std::get_if<image::ImageError>(&read)) return fail("ground truth: " + e->what());
  image::Image img = std::move(std::get<image::Image>(read));
  if (!has_exr_magic(path))
    return fail("ground truth: " + path +
                " is not an EXR: load the linear radiance of sss-reference --method random-walk --out NAME.exr");
  if (const std::string* content = attribute(img, "sssContent"); content && *content != "mean")
    return fail("ground truth: " + path + " holds the ground truth's " + *content +
                " (sssContent), not its mean: load the .exr written by --out");
  const std::uint32_t w = live.width > 0 ? live.width : r.options().width;
  const std::uint32_t h = live.height > 0 ? live.height : r.options().height;
  if (std::uint32_t(img.width) != w || std::uint32_t(img.height) != h)
    return fail("ground truth: " + path + " is " + size_text(img.width, img.height) +
                " but the view is " + size_text(int(w), int(h)) +
                ": a truth compares only at its own size (resize the window to " +
                size_text(img.width, img.height) + ", or render one with sss-reference --method "
                "random-walk --width " + std::to_string(w) + " --height " + std::to_string(h) + ")");
  truth_ = std::move(img);
  truth_source_ = path;
  truth_exposure_ = -1.0f;
  truth_image_ = {};
  try {
    show_truth(r.options().exposure);
  } catch (const std::exception& e) {
    truth_.reset();
    return fail("ground truth: " + std::string(e.what()));
  }
  std::ostringstream m;
  m << "ground truth: " << path << " (" << size_text(truth_->width, truth_->height);
  if (const std::string* spp = attribute(*truth_, "sssSpp")) m << ", " << *spp << " spp";
  if (const std::string* se = attribute(*truth_, "sssRelativeStandardError"))
    m << ", relative standard error " << std::atof(se->c_str()) * 100.0 << "%";
  m << ")";
  truth_info_ = truth_message_ = m.str();
  truth_error_ = false;
  // The truth cannot say which camera it saw; its settings name the scene, at least.
  if (const std::string* settings = attribute(*truth_, "sssSettings")) {
    const std::string scene = settings->substr(0, settings->find(' '));
    if (!scene.empty() && scene != live.source && is_builtin(scene))
      truth_warning_ = "rendered from " + scene + ", the view shows " + live.source;
  }
  copy_to(truth_path_, sizeof truth_path_, path);
  for (int p = 1; p < kPairs; ++p) results_[p].reset();
  compare_pending_ = true;
  return true;
}

void ViewerTools::clear_truth() {
  truth_.reset();
  truth_source_.clear();
  truth_display_ = {};
  truth_image_ = {};
  truth_exposure_ = -1.0f;
  truth_message_.clear();
  truth_info_.clear();
  truth_warning_.clear();
  truth_error_ = false;
  for (int p = 1; p < kPairs; ++p) results_[p].reset();
  if (pair_ != Pair::FrameVsReference) {
    pair_ = Pair::FrameVsReference;
    render_map();
  }
  if (view_ == 4) view_ = 0;
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
  if (estimator_ == int(ReferenceEstimator::Probe))  // the probe at its defaults, as auto sets it
    o = reference::with_choice(o, {reference::Estimator::Probe, o.spacing_mfp});
  job_key_ = live_key(r, live);
  compare_error_.clear();
  job_.start(std::move(s), o, estimator_ == int(ReferenceEstimator::Auto));
}

void ViewerTools::poll(renderer::Renderer& r, const LiveState& live) {
  if (std::optional<reference::ReferenceImage> done = job_.take()) {
    reference_ = std::move(done);
    reference_key_ = job_key_;
    quantize(reference_->display);
    try {
      reference_image_ = upload(reference_->display, "compare reference");
    } catch (const std::exception& e) {
      compare_error_ = e.what();
    }
    compare_pending_ = live_key(r, live) == reference_key_ || truth_.has_value();
    if (view_ == 0) view_ = 1;
  }
  // Compare the full-size frame (not a scaled one drawn while the view moves).
  const std::uint32_t w = live.width > 0 ? live.width : r.options().width;
  const std::uint32_t h = live.height > 0 ? live.height : r.options().height;
  if (compare_pending_ && (reference_ || truth_) && r.options().width == w && r.options().height == h) {
    compare_pending_ = false;
    compare_now(r, live);
  }
  if (std::string e = job_.take_error(); !e.empty()) compare_error_ = "reference: " + e;
}

void ViewerTools::draw_compare(renderer::Renderer& r, const LiveState& live) {
  if (expand_) ImGui::SetNextItemOpen(true);
  expand_ = false;
  if (!ImGui::CollapsingHeader("Compare with the CPU reference")) return;

  ImGui::Combo("estimator", &estimator_, "auto\0octree\0probe\0");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("auto: as sss-reference does, per view: the octree, with finer points where the "
                      "pixels are finer than its spacing, or the per-pixel probe where that many points "
                      "would not fit. probe: %llu batches per pixel, no point spacing, slower.",
                      (unsigned long long)reference::kDefaultProbeBatches);
  if (estimator_ != int(ReferenceEstimator::Probe)) {
    ImGui::SliderFloat("spacing (mfp)", &spacing_mfp_, 0.25f, 2.0f, "%.2f");
    ImGui::SliderFloat("error bound (sr)", &error_bound_, 0.05f, 1.0f, "%.2f");
  }
  if (job_.running()) {
    ImGui::ProgressBar(float(job_.fraction()), ImVec2(-1, 0), job_.progress().c_str());
    if (ImGui::Button("Cancel")) job_.cancel();
  } else if (ImGui::Button("Render reference of this view")) {
    start_reference(r, live);
  }
  if (!compare_error_.empty()) colored_text_wrapped(kErrorColor, compare_error_.c_str());
  if (const std::string chose = job_.chosen(); !chose.empty()) ImGui::TextWrapped("auto chose %s", chose.c_str());
  bool stale = false;
  if (reference_) {
    const reference::ReferenceStats& st = reference_->stats;
    if (st.spp > 0)
      ImGui::Text("reference: probe, %llu batches, frame's relative standard error %.2f%%, %.1f s",
                  (unsigned long long)st.spp, 100.0 * st.relative_standard_error, st.total_ms / 1000.0);
    else
      ImGui::Text("reference: %zu points, %.1f s", st.points, st.total_ms / 1000.0);
    stale = live_key(r, live) != reference_key_;
    if (stale) colored_text_wrapped(kWarningColor, "The view or a material changed since: render again.");
  }
  draw_truth(r, live);
  if (!reference_ && !truth_) return;

  ImGui::Separator();
  ImGui::RadioButton("live", &view_, 0);
  if (reference_) {
    ImGui::SameLine();
    ImGui::RadioButton("split", &view_, 1);
    ImGui::SameLine();
    ImGui::RadioButton("reference", &view_, 2);
  }
  if (truth_) {
    ImGui::SameLine();
    ImGui::RadioButton("truth", &view_, 4);
  }
  ImGui::SameLine();
  ImGui::RadioButton("error", &view_, 3);
  if (view_ == 1 && reference_) {
    ImGui::SliderFloat("split", &split_, 0.0f, 1.0f, "%.2f");
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImDrawList* fg = ImGui::GetForegroundDrawList();
    fg->AddLine(ImVec2(split_ * size.x, 0.0f), ImVec2(split_ * size.x, size.y),
                IM_COL32(255, 255, 255, 200), 1.5f);
    fg->AddText(ImVec2(split_ * size.x - 76.0f, size.y - 22.0f), IM_COL32_WHITE, "reference");
    fg->AddText(ImVec2(split_ * size.x + 8.0f, size.y - 22.0f), IM_COL32_WHITE, "live");
    ImGui::TextDisabled("left: reference, right: live frame");
  }
  if (((reference_ && !stale) || truth_) && ImGui::Button("Compare the current frame"))
    compare_pending_ = true;
  draw_metrics();
  if (view_ == 3) draw_map_controls();
}

void ViewerTools::draw_truth(const renderer::Renderer& r, const LiveState& live) {
  ImGui::Separator();
  ImGui::TextWrapped("Ground truth: the EXR of sss-reference --method random-walk of this view, "
                     "at the window's size");
  const bool enter = ImGui::InputText("##truth", truth_path_, sizeof truth_path_,
                                      ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if (ImGui::Button("Load") || enter) (void)load_truth(truth_path_, r, live);
  if (truth_) {
    ImGui::SameLine();
    if (ImGui::Button("Clear")) clear_truth();
  }
  if (!truth_message_.empty()) {
    if (truth_error_) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", truth_message_.c_str());
    if (truth_error_) ImGui::PopStyleColor();
  }
  if (!truth_warning_.empty()) colored_text_wrapped(kWarningColor, truth_warning_.c_str());
}

}  // namespace sss::app
