// The checks every estimator of the diffusion reference shares (ReferenceRenderer.cpp,
// EstimatorChoice.cpp). Internal to reference.
#pragma once

#include "reference/ReferenceRenderer.h"

#include "profiles/Medium.h"

namespace sss::reference::detail {

// std::invalid_argument naming the option when `o` cannot be rendered.
void check_options(const ReferenceOptions& o);
// std::invalid_argument when the scene has no camera or a broken mesh or index.
void check_scene(const scene::Scene& s);
// Whether the GPU's sky occlusion applies: an environment, the GPU-shadow mode and
// ReferenceOptions::sky_occlusion; then RayScene::set_sky_transfers before lighting.
inline bool gpu_sky_occlusion(const scene::Scene& s, const ReferenceOptions& o) {
  return s.environment && o.shadows == Shadows::ShadowMap && o.sky_occlusion;
}
// The smallest reduced mean free path over the medium's channels, in mm.
double smallest_mfp(const profiles::Medium& m);

}  // namespace sss::reference::detail
