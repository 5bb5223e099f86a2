// The separable kernel's tabulated quadrature (SeparableKernel.h: R sampled once on a
// log grid) against the exact one (edge_response on the model itself): the weights agree
// to 1e-6 (absolute; they sum to 1), the range to 1e-5 relative, on the presets under the
// models whose R is numerical (pbd, multipole), and Auto picks Tabulated for them only.
#include "profiles/EdgeResponse.h"
#include "profiles/Presets.h"
#include "profiles/SeparableKernel.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

using namespace sss::profiles;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Comparison {
  double max_weight_diff = 0.0, range_rel_diff = 0.0, exact_s = 0.0, tabulated_s = 0.0;
};

Comparison compare(const RgbProfile& profile, int taps) {
  Comparison out;
  auto t0 = std::chrono::steady_clock::now();
  const SeparableKernel exact = make_separable_kernel(profile, taps, 0.0, KernelQuadrature::Exact);
  out.exact_s = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const SeparableKernel tab = make_separable_kernel(profile, taps, 0.0, KernelQuadrature::Tabulated);
  out.tabulated_s = seconds_since(t0);
  EXPECT_EQ(exact.weights.size(), tab.weights.size());
  for (std::size_t i = 0; i < exact.weights.size() && i < tab.weights.size(); ++i)
    for (int c = 0; c < 3; ++c)
      out.max_weight_diff =
          std::max(out.max_weight_diff, std::fabs(exact.weights[i][c] - tab.weights[i][c]));
  out.range_rel_diff = std::fabs(tab.range_mm - exact.range_mm) / exact.range_mm;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (const auto& w : tab.weights) sum += w[c];
    EXPECT_NEAR(sum, 1.0, 1e-14) << c;
    EXPECT_EQ(tab.total_reflectance[c], exact.total_reflectance[c]);
  }
  return out;
}

}  // namespace

TEST(SeparableKernelQuadrature, TabulatedMatchesExactForPbd) {
  double worst = 0.0, worst_range = 0.0, exact_s = 0.0, tab_s = 0.0;
  for (const char* name : {"skin1", "marble", "ketchup", "apple", "skimmilk"}) {
    const RgbProfile profile(Model::Pbd, preset_medium(*find_preset(name)));
    const Comparison c = compare(profile, 17);
    EXPECT_LT(c.max_weight_diff, 1e-6) << name;
    EXPECT_LT(c.range_rel_diff, 1e-5) << name;
    worst = std::max(worst, c.max_weight_diff);
    worst_range = std::max(worst_range, c.range_rel_diff);
    exact_s += c.exact_s;
    tab_s += c.tabulated_s;
  }
  std::printf("pbd, 17 taps, 5 presets: max |weight diff| %.3g, range %.3g relative; mean "
              "exact %.1f ms, tabulated %.1f ms\n",
              worst, worst_range, 1e3 * exact_s / 5, 1e3 * tab_s / 5);
  EXPECT_LT(tab_s, 0.25 * exact_s);
}

TEST(SeparableKernelQuadrature, TabulatedMatchesExactForMultipole) {
  for (const char* name : {"skin1", "marble"}) {
    Medium m = preset_medium(*find_preset(name));
    m.thickness_mm = 5.0;
    const RgbProfile profile(Model::Multipole, m);
    const Comparison c = compare(profile, 17);
    EXPECT_LT(c.max_weight_diff, 1e-6) << name;
    EXPECT_LT(c.range_rel_diff, 1e-5) << name;
    std::printf("multipole %s: max |weight diff| %.3g, exact %.1f ms, tabulated %.1f ms\n", name,
                c.max_weight_diff, 1e3 * c.exact_s, 1e3 * c.tabulated_s);
  }
}

TEST(SeparableKernelQuadrature, AutoTabulatesOnlyNumericalProfiles) {
  const Medium skin = preset_medium(*find_preset("skin1"));
  for (Model model : {Model::Dipole, Model::BetterDipole, Model::Burley}) {
    const RgbProfile profile(model, skin);
    const SeparableKernel a = make_separable_kernel(profile, 9);
    const SeparableKernel e = make_separable_kernel(profile, 9, 0.0, KernelQuadrature::Exact);
    EXPECT_EQ(a.range_mm, e.range_mm) << model_name(model);
    EXPECT_EQ(a.weights, e.weights) << model_name(model);
  }
  const RgbProfile pbd(Model::Pbd, skin);
  const SeparableKernel a = make_separable_kernel(pbd, 9);
  const SeparableKernel t = make_separable_kernel(pbd, 9, 0.0, KernelQuadrature::Tabulated);
  EXPECT_EQ(a.range_mm, t.range_mm);
  EXPECT_EQ(a.weights, t.weights);
}
