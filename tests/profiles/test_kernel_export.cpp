#include "profiles/EdgeResponse.h"
#include "profiles/KernelExport.h"
#include "profiles/Presets.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

using namespace sss::profiles;

namespace {

RgbProfile skin1(Model model = Model::BetterDipole) {
  return RgbProfile(model, preset_medium(*find_preset("skin1")));
}

GaussianFit skin1_fit(int n = 6) {
  FitOptions opt;
  opt.gaussians = n;
  return fit_gaussians(make_fit_target(skin1()), opt);
}

std::set<std::string> keys(const nlohmann::json& j) {
  std::set<std::string> out;
  for (auto it = j.begin(); it != j.end(); ++it) out.insert(it.key());
  return out;
}

}  // namespace

TEST(SeparableKernel, SumsToOneSymmetricWithATapAtZero) {
  const RgbProfile profile = skin1();
  const int taps = 17, half = 8;
  const SeparableKernel k = make_separable_kernel(profile, taps);
  ASSERT_EQ(k.offsets_mm.size(), 17u);
  ASSERT_EQ(k.weights.size(), 17u);
  EXPECT_EQ(k.offsets_mm[half], 0.0);
  EXPECT_FALSE(std::signbit(k.offsets_mm[half]));  // +0.0: never printed as "-0.00000"
  for (int i = 0; i < taps; ++i) {
    EXPECT_EQ(k.offsets_mm[i], -k.offsets_mm[taps - 1 - i]) << i;
    if (i > 0) {
      EXPECT_LT(k.offsets_mm[i - 1], k.offsets_mm[i]) << i;
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(k.weights[i][c], k.weights[taps - 1 - i][c]) << i;
      EXPECT_GE(k.weights[i][c], 0.0) << i;
    }
  }
  // Jimenez's quadratic spacing.
  for (int i = 0; i <= half; ++i) {
    const double t = static_cast<double>(i) / half;
    EXPECT_NEAR(k.offsets_mm[half + i], k.range_mm * t * t, 1e-15 * k.range_mm) << i;
  }
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (const auto& w : k.weights) sum += w[c];
    // A telescoping sum of 17 rounded differences, each within 1 ulp of the total.
    EXPECT_NEAR(sum, 1.0, 17 * 2.3e-16) << c;
    EXPECT_EQ(k.total_reflectance[c], profile.total_reflectance()[c]);
  }
  // The automatic range holds 99.9% of the widest channel's marginal: M(range) = 5e-4·T
  // there (bisection to 1e-9 relative in x moves M by < 1e-9·T), and <= for the others.
  double widest = 0.0;
  const sss::Rgb m = edge_response(profile, k.range_mm);
  for (int c = 0; c < 3; ++c) {
    const double fraction = m[c] / profile.total_reflectance()[c];
    EXPECT_LE(fraction, 5e-4 + 1e-9) << c;
    widest = std::max(widest, fraction);
  }
  EXPECT_NEAR(widest, 5e-4, 1e-9);
}

TEST(SeparableKernel, ReproducesTheEdgeResponseOfAStep) {
  // Convolve the step in(x) = 1 for x < 0 (½ at 0) with the taps:
  //   out(x) = T Σ_k w_k in(x - x_k).
  // At a cell boundary b_j (the midpoint between taps j and j+1) exactly the taps beyond
  // it are lit, so out(b_j) = M(b_j) up to rounding (1e-14·T for 17 terms). At a tap x_j
  // the tap itself counts ½, so out(x_j) = ½(M(b_{j-1}) + M(b_j)); M(x_j) lies between
  // those two values (M decreases), so out(x_j) is within ½ T w_j of it.
  const RgbProfile profile = skin1();
  const SeparableKernel k = make_separable_kernel(profile, 17);
  auto step = [](double x) { return x < 0.0 ? 1.0 : (x == 0.0 ? 0.5 : 0.0); };
  auto convolve = [&](double x, int c) {
    double out = 0.0;
    for (std::size_t i = 0; i < k.offsets_mm.size(); ++i) out += k.weights[i][c] * step(x - k.offsets_mm[i]);
    return k.total_reflectance[c] * out;
  };
  for (std::size_t j = 0; j < k.offsets_mm.size(); ++j) {
    const double x = k.offsets_mm[j];
    const sss::Rgb m = edge_response(profile, x);
    for (int c = 0; c < 3; ++c) {
      const double T = k.total_reflectance[c];
      EXPECT_NEAR(convolve(x, c), m[c], 0.5 * T * k.weights[j][c] + 1e-14 * T) << j << c;
    }
    if (j + 1 < k.offsets_mm.size()) {
      const double b = 0.5 * (k.offsets_mm[j] + k.offsets_mm[j + 1]);
      const sss::Rgb mb = edge_response(profile, b);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(convolve(b, c), mb[c], 1e-14 * k.total_reflectance[c]) << j << c;
    }
  }
}

TEST(SeparableKernel, RejectsBadTapCounts) {
  const RgbProfile profile = skin1(Model::Dipole);
  for (int taps : {-1, 0, 1, 2, 16})
    EXPECT_THROW(make_separable_kernel(profile, taps), std::invalid_argument) << taps;
  const SeparableKernel k = make_separable_kernel(profile, 3, 2.0);
  EXPECT_EQ(k.range_mm, 2.0);
  EXPECT_EQ(k.offsets_mm.back(), 2.0);
}

TEST(KernelExport, JsonParsesBackWithTheContractKeys) {
  const GaussianFit fit = skin1_fit();
  const SeparableKernel sep = make_separable_kernel(skin1(), 9);
  // Quotes, a backslash and a newline must survive the escaping.
  const KernelInfo info{"better-dipole", "skin1 \"preset\"\\ with\nnewline"};
  for (const SeparableKernel* s : {static_cast<const SeparableKernel*>(nullptr), &sep}) {
    const nlohmann::json j = nlohmann::json::parse(kernel_to_json(fit, info, s));
    std::set<std::string> expected = {"model",   "medium",           "variances_mm2",
                                      "weights", "total_reflectance", "relative_error",
                                      "resolution_mm"};
    if (s) expected.insert("separable");
    EXPECT_EQ(keys(j), expected);
    EXPECT_EQ(j["model"], info.model);
    EXPECT_EQ(j["medium"], info.medium);
    // %.17g round-trips every double exactly.
    ASSERT_EQ(j["variances_mm2"].size(), fit.variances_mm2.size());
    ASSERT_EQ(j["weights"].size(), fit.weights.size());
    for (std::size_t i = 0; i < fit.variances_mm2.size(); ++i) {
      EXPECT_EQ(j["variances_mm2"][i].get<double>(), fit.variances_mm2[i]);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(j["weights"][i][c].get<double>(), fit.weights[i][c]);
    }
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(j["total_reflectance"][c].get<double>(), fit.total_reflectance[c]);
      EXPECT_EQ(j["relative_error"][c].get<double>(), fit.relative_error[c]);
    }
    if (s) {
      const auto& js = j["separable"];
      EXPECT_EQ(keys(js), (std::set<std::string>{"offsets_mm", "weights", "total_reflectance"}));
      ASSERT_EQ(js["offsets_mm"].size(), sep.offsets_mm.size());
      for (std::size_t i = 0; i < sep.offsets_mm.size(); ++i) {
        EXPECT_EQ(js["offsets_mm"][i].get<double>(), sep.offsets_mm[i]);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(js["weights"][i][c].get<double>(), sep.weights[i][c]);
      }
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(js["total_reflectance"][c].get<double>(), sep.total_reflectance[c]);
    }
  }
}

TEST(KernelExport, CHeaderCompilesAndItsWeightsSumToTheTotal) {
  if (std::system("command -v cc > /dev/null 2>&1") != 0) GTEST_SKIP() << "no C compiler (cc)";
  const GaussianFit fit = skin1_fit();
  const SeparableKernel sep = make_separable_kernel(skin1(), 11);
  const std::string header = kernel_to_c_header(fit, {"better-dipole", "skin1 */ tricky"}, &sep, "myk");

  const auto dir = std::filesystem::temp_directory_path() /
                   ("sss_kernel_test_" + std::to_string(std::random_device{}()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "myk.h") << header;
  // Included twice: the include guard must hold.
  std::ofstream(dir / "main.c") << R"(#include <stdio.h>
#include "myk.h"
#include "myk.h"
int main(void) {
  int c, i;
  for (c = 0; c < 3; ++c) {
    double sum = 0.0, sep = 0.0;
    for (i = 0; i < MYK_COUNT; ++i) sum += myk_weights[i][c];
    for (i = 0; i < MYK_SEPARABLE_TAPS; ++i) sep += myk_separable_weights[i][c];
    printf("%.17g %.17g %.17g\n", sum, (double)myk_total_reflectance[c], sep);
  }
  printf("%d %d\n", MYK_COUNT, MYK_SEPARABLE_TAPS);
  return 0;
}
)";
  const std::string exe = (dir / "main").string();
  const std::string compile = "cc -std=c99 -Wall -Wextra -pedantic -Werror -o '" + exe + "' '" +
                              (dir / "main.c").string() + "' 2>&1";
  ASSERT_EQ(std::system(compile.c_str()), 0) << "compiling the header failed:\n" << header;
  FILE* pipe = popen(("'" + exe + "'").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[256];
  while (std::fgets(buf, sizeof buf, pipe)) output += buf;
  ASSERT_EQ(pclose(pipe), 0);
  std::filesystem::remove_all(dir);

  std::istringstream in(output);
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0, total = 0.0, sep_sum = 0.0;
    in >> sum >> total >> sep_sum;
    const double T = fit.total_reflectance[c];
    // Each float weight is within 2^-24 (relative) of its double, so the float sum (in
    // double, exact enough) is within 2^-24·T of the double sum, which is T to 1e-15·T.
    // Same for the stored total, and for the separable weights against 1.
    EXPECT_NEAR(sum, T, 0x1p-24 * T + 1e-15 * T) << c;
    EXPECT_NEAR(total, T, 0x1p-24 * T) << c;
    EXPECT_NEAR(sep_sum, 1.0, 0x1p-24 + 11 * 2.3e-16) << c;
  }
  int count = 0, taps = 0;
  in >> count >> taps;
  EXPECT_EQ(count, 6);
  EXPECT_EQ(taps, 11);
}

TEST(KernelExport, CHeaderRejectsABadPrefix) {
  const GaussianFit fit = skin1_fit(2);
  for (const char* prefix : {"", "9lives", "has space", "dash-ed"})
    EXPECT_THROW(kernel_to_c_header(fit, {}, nullptr, prefix), std::invalid_argument) << prefix;
  EXPECT_NO_THROW(kernel_to_c_header(fit, {}, nullptr, "_ok9"));
}
