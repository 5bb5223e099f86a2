// sss_fuzz_sss_extras: the materials[i].extras.sss block of a glTF (FuzzTargets.h).
#include "FuzzSupport.h"
#include "FuzzTargets.h"

#include "scene/SssExtras.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <string_view>

int sss_fuzz_sss_extras(const std::uint8_t* data, std::size_t size) {
  using namespace sss::scene;
  const std::string_view text(reinterpret_cast<const char*>(data), size);

  // The text entry point (it parses without exceptions itself).
  auto from_text = parse_sss_extras_text(text);

  // The JSON entry point, as the glTF loader calls it: nlohmann without exceptions; a
  // parse failure is a discarded value, not an exception.
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;
  auto parsed = parse_sss_extras(j);
  if (auto* m = std::get_if<SssMaterial>(&parsed)) {
    // An accepted material is usable: a valid medium, a Gaussian count in range, and it
    // reads back as itself through the exporter's block (SssExtras.h).
    const sss::profiles::Medium e = m->effective_medium();
    sss::fuzz::fuzz_check(!e.validate(), "an accepted material has a valid effective medium");
    sss::fuzz::fuzz_check(m->gaussians >= kMinGaussians && m->gaussians <= kMaxGaussians,
                          "gaussians in 1..8");
    sss::fuzz::fuzz_check(std::isfinite(m->scale) && m->scale > 0.0, "scale is finite and > 0");
    // A stack (extras.sss.layers) is a valid one, and its top layer is the medium.
    if (!m->layers.empty()) {
      sss::fuzz::fuzz_check(!sss::profiles::validate_layers(m->layers), "an accepted stack is valid");
      sss::fuzz::fuzz_check(m->model == sss::profiles::Model::Layered, "a stack's model is layered");
      sss::fuzz::fuzz_check(m->medium.sigma_a == m->layers.front().sigma_a &&
                                m->medium.sigma_s == m->layers.front().sigma_s,
                            "a stack's medium is its top layer");
    }
    auto again = parse_sss_extras(sss_extras_json(*m));
    sss::fuzz::fuzz_check(std::holds_alternative<SssMaterial>(again),
                          "the exported block of an accepted material is accepted");
    sss::fuzz::fuzz_check(std::holds_alternative<SssMaterial>(from_text),
                          "text and JSON entry points agree");
    sss::fuzz::count_accepted();
  }
  return 0;
}
