// The material editor's stack operations (issue 19): split, remove, move, replace, and a
// layer's preset. MaterialEditor.h says what each does; each applies the stack it makes.
#include "MaterialEditor.h"

#include "profiles/Presets.h"

#include <algorithm>
#include <string>

namespace sss::app {

namespace {

// The thinnest a layer of these coefficients may be (validate_layers: thicker than 1/σt'
// in every channel), doubled so that a copy stays valid, and at least 0.1 mm.
float copy_thickness(const LayerEdit& l) {
  double mfp = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double st = double(l.sigma_a[c]) + double(l.sigma_s[c]) * (1.0 - double(l.g[c]));
    if (st > 0.0) mfp = std::max(mfp, 1.0 / st);
  }
  return static_cast<float>(std::max(0.1, 2.0 * mfp));
}

}  // namespace

bool MaterialEditor::add_layer(std::size_t edit, std::size_t at) {
  MaterialEdit& e = edits_.at(edit);
  const bool one_medium = e.layers.empty();
  if (one_medium) {  // the one medium becomes the stack's only layer first
    if (e.kind == SourceKind::Artist || e.kind == SourceKind::OpenPbr) {
      e.error = std::string("add layer: ") +
                (e.kind == SourceKind::Artist ? "an artist colour + mfp" : "OpenPBR's subsurface") +
                " describes one medium; switch to coefficients first";
      return false;
    }
    LayerEdit l{e.sigma_a, e.sigma_s, e.g, e.thickness_mm > 0.0f ? e.thickness_mm : 0.0f};
    e.layers.push_back(l);
    at = 0;
  }
  if (at >= e.layers.size()) {
    e.error = "add layer: no layer " + std::to_string(at);
    return false;
  }
  if (e.layers.size() >= static_cast<std::size_t>(profiles::kMaxLayers)) {
    e.error = "add layer: at most " + std::to_string(profiles::kMaxLayers) + " layers";
    return false;
  }
  LayerEdit top = e.layers[at];
  const float min_half = 0.5f * copy_thickness(top);  // one 1/σt', at least 0.05 mm
  if (top.thickness_mm > 0.0f && 0.5f * top.thickness_mm > min_half) {
    top.thickness_mm *= 0.5f;
    e.layers[at].thickness_mm = top.thickness_mm;
  } else {
    top.thickness_mm = copy_thickness(top);
  }
  e.layers.insert(e.layers.begin() + static_cast<std::ptrdiff_t>(at), top);
  const SourceKind kind = e.kind;
  e.kind = SourceKind::Coefficients;
  if (apply(edit)) return true;
  if (one_medium) {  // e.g. a slab thinner than a layer may be: stay the medium it was
    e.layers.clear();
    e.kind = kind;
  }
  return false;
}

bool MaterialEditor::remove_layer(std::size_t edit, std::size_t at) {
  MaterialEdit& e = edits_.at(edit);
  if (at >= e.layers.size()) {
    e.error = "remove layer: no layer " + std::to_string(at);
    return false;
  }
  const LayerEdit removed = e.layers[at];
  e.layers.erase(e.layers.begin() + static_cast<std::ptrdiff_t>(at));
  // One layer left (or a stack of one, read from a file, emptied): one medium again, with
  // that layer's coefficients, under the default model.
  if (e.layers.size() <= 1) {
    const LayerEdit l = e.layers.empty() ? removed : e.layers.front();
    e.sigma_a = l.sigma_a;
    e.sigma_s = l.sigma_s;
    e.g = l.g;
    e.thickness_mm = l.thickness_mm;
    e.model = std::max(model_index(profiles::kDefaultModel), 0);
    e.layers.clear();
  }
  e.kind = SourceKind::Coefficients;
  return apply(edit);
}

bool MaterialEditor::move_layer(std::size_t edit, std::size_t at, int by) {
  MaterialEdit& e = edits_.at(edit);
  const long to = static_cast<long>(at) + by;
  if (at >= e.layers.size() || (by != -1 && by != 1) || to < 0 ||
      to >= static_cast<long>(e.layers.size())) {
    e.error = "move layer: cannot move layer " + std::to_string(at) + " by " + std::to_string(by);
    return false;
  }
  std::swap(e.layers[at], e.layers[static_cast<std::size_t>(to)]);
  return apply(edit);
}

bool MaterialEditor::set_layers(std::size_t edit, const profiles::LayerStack& stack) {
  MaterialEdit& e = edits_.at(edit);
  if (auto err = profiles::validate_layers(stack)) {
    e.error = err->what();
    return false;
  }
  fill_coefficients(e, stack.front());
  fill_layers(e, stack);
  return apply(edit);
}

bool MaterialEditor::set_layer_preset(std::size_t edit, std::size_t at, int preset, bool adopt_eta) {
  MaterialEdit& e = edits_.at(edit);
  e.eta_offer.reset();
  const auto all = profiles::presets();
  if (at >= e.layers.size()) {
    e.error = "layer preset: no layer " + std::to_string(at);
    return false;
  }
  const std::string field = "layers[" + std::to_string(at) + "].preset";
  if (preset < 0 || preset >= static_cast<int>(all.size())) {
    e.error = field + ": no preset " + std::to_string(preset);
    return false;
  }
  const profiles::Preset& p = all[static_cast<std::size_t>(preset)];
  const profiles::Medium m = profiles::preset_medium(p);
  std::array<float, 3> eta{};
  for (int c = 0; c < 3; ++c) eta[c] = static_cast<float>(m.eta[c]);
  if (eta != e.eta && !adopt_eta) {
    const std::size_t c = eta[0] != e.eta[0] ? 0 : eta[1] != e.eta[1] ? 1 : 2;  // the first that differs
    e.error = field + ": preset " + std::string(p.name) + " has eta " + message_number(m.eta[c]) +
              " but the stack's is " + message_number(e.eta[c]) +
              ": every layer of a stack has the same eta (set \"eta (all)\" first, or give the whole stack "
              "the preset's with the button above)";
    e.eta_offer = MaterialEdit::EtaOffer{at, preset, eta};
    return false;
  }
  const LayerEdit before = e.layers[at];
  const std::array<float, 3> eta_before = e.eta;
  LayerEdit& l = e.layers[at];
  for (int c = 0; c < 3; ++c) {
    l.sigma_a[c] = static_cast<float>(m.sigma_a[c]);
    l.sigma_s[c] = static_cast<float>(m.sigma_s[c]);
    l.g[c] = static_cast<float>(m.g[c]);
  }
  l.preset = preset;
  e.eta = eta;
  if (apply(edit)) return true;
  e.layers[at] = before;  // apply() set the error and submitted nothing
  e.eta = eta_before;
  return false;
}

}  // namespace sss::app
