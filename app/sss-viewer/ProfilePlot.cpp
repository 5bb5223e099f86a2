#include "ProfilePlot.h"

#include "profiles/Profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sss::app {

ProfilePlot make_profile_plot(const scene::SssMaterial& material, const profiles::GaussianFit& fit,
                              int samples) {
  if (samples < 2) throw std::invalid_argument("make_profile_plot: samples must be >= 2");
  if (!material.enabled) throw std::invalid_argument("make_profile_plot: not an SSS material");
  const profiles::RgbProfile profile = material.profile();
  const double lo = std::log(1e-2 * profile.inner_radius());
  const double hi = std::log(profile.support_radius());
  ProfilePlot p;
  p.fit_relative_error = fit.relative_error;
  const bool transmits = material.transmits();
  for (int i = 0; i < samples; ++i) {
    const double r = std::exp(lo + (hi - lo) * i / (samples - 1));
    const Rgb model = profile.reflectance(r);
    const Rgb approx = fit.evaluate(r);
    Rgb m{}, f{}, e{};
    for (int c = 0; c < 3; ++c) {
      m[c] = r * model[c];
      f[c] = r * approx[c];
      e[c] = model[c] > 0.0 ? std::fabs(approx[c] - model[c]) / model[c] : 0.0;
    }
    p.r_mm.push_back(r);
    p.model_rR.push_back(m);
    p.fit_rR.push_back(f);
    p.rel_error.push_back(e);
    if (transmits) {
      const Rgb t = profile.transmittance(r);
      p.model_rT.push_back({r * t[0], r * t[1], r * t[2]});
    }
  }
  return p;
}

LogRange log_range(const std::vector<double>& v, int max_decades) {
  double top = 0.0;
  for (double x : v)
    if (std::isfinite(x)) top = std::max(top, x);
  if (!(top > 0.0)) return {};
  double bottom = top;
  for (double x : v)
    if (x > 0.0 && std::isfinite(x)) bottom = std::min(bottom, x);
  LogRange r;
  r.hi = static_cast<int>(std::ceil(std::log10(top)));
  r.lo = std::max(static_cast<int>(std::floor(std::log10(bottom))), r.hi - max_decades);
  if (r.lo >= r.hi) r.lo = r.hi - 1;
  return r;
}

}  // namespace sss::app
