// The data of the viewer's profile plot, without ImGui: r·R(r) of a material's model and
// of its sum-of-Gaussians fit, per channel, sampled on a log grid of r (mm), and the fit's
// relative error |fit − model| / model at each r. Plotted log-log (Ui.cpp); r·R is what
// the fit minimises (GaussianFit.h: relative L2 error of r·R(r) in dr).
#pragma once

#include "profiles/GaussianFit.h"
#include "scene/Material.h"

#include <vector>

namespace sss::app {

struct ProfilePlot {
  std::vector<double> r_mm;     // ascending, log-spaced, in object mm
  std::vector<Rgb> model_rR;    // r·R(r) of the model, mm^-1
  std::vector<Rgb> fit_rR;      // r·R̃(r) of the fit
  std::vector<Rgb> rel_error;   // |fit − model| / model (0 where the model is 0)
  // r·T(r) of the model at the same radii: the light leaving the far face of a slab or of
  // a stack with a finite bottom (SssMaterial::transmits()); empty for a half-space and
  // for a model that gives a slab no T(r).
  std::vector<Rgb> model_rT;
  Rgb fit_relative_error{};     // the fit's own L2 measure (GaussianFit::relative_error)
};

// `samples` radii from 1e-2·inner_radius to support_radius of the material's effective
// medium (scale folded in, as the renderer uses it). `fit` must be that medium's fit
// (MaterialData::profiles[i]->fit). Throws std::invalid_argument for samples < 2 or a
// disabled material.
ProfilePlot make_profile_plot(const scene::SssMaterial& material, const profiles::GaussianFit& fit,
                              int samples = 64);

// Log-log axes: the decades [10^lo, 10^hi] that hold the values > 0 of `v` (at least one
// decade wide, at most `max_decades` down from the largest value).
struct LogRange {
  int lo = 0, hi = 1;
};
LogRange log_range(const std::vector<double>& v, int max_decades = 6);

}  // namespace sss::app
