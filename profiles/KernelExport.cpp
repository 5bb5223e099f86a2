#include "profiles/KernelExport.h"

#include "profiles/EdgeResponse.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <string_view>

namespace sss::profiles {

namespace {

// The marginal's tails beyond ±range hold at most this fraction of its energy per side:
// 2·5e-4 = 0.1%, i.e. the range holds 99.9%.
constexpr double kTailFraction = 5e-4;

// The x > 0 where M(x) = fraction·total (M decreases from total/2 at 0 to 0 at the
// support), by bisection to a relative width of 1e-9.
double tail_radius(const RadialProfile& p, double fraction) {
  const double target = fraction * p.total_reflectance();
  double lo = 0.0, hi = p.support_radius();
  while (hi - lo > 1e-9 * hi) {
    const double mid = 0.5 * (lo + hi);
    (edge_response(p, mid) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";  // JSON has no NaN or infinity
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// Strings are built by appending: GCC 12 flags `"literal" + std::string&&` with a false
// -Wrestrict positive, and appending is cheaper anyway.
std::string json_rgb(const Rgb& v) {
  std::string out = "[";
  for (int c = 0; c < 3; ++c) {
    if (c) out += ", ";
    out += number(v[c]);
  }
  out += "]";
  return out;
}

std::string json_list(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) out += ", ";
    out += number(v[i]);
  }
  out += "]";
  return out;
}

std::string json_rgb_list(const std::vector<Rgb>& v, const std::string& indent) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    out += i ? ",\n" : "\n";
    out += indent;
    out += "  ";
    out += json_rgb(v[i]);
  }
  out += "\n";
  out += indent;
  out += "]";
  return out;
}

// A C float literal that round-trips the float nearest to v (9 significant digits).
std::string c_float(double v) {
  if (!std::isfinite(v))
    throw std::invalid_argument("kernel_to_c_header: a value is not finite");
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9ef", v);
  return buf;
}

std::string c_rgb(const Rgb& v) {
  std::string out = "{";
  for (int c = 0; c < 3; ++c) {
    if (c) out += ", ";
    out += c_float(v[c]);
  }
  out += "}";
  return out;
}

std::string c_list(const std::vector<double>& v) {
  std::string out = "{";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) out += ", ";
    out += c_float(v[i]);
  }
  out += "}";
  return out;
}

std::string c_rgb_list(const std::vector<Rgb>& v) {
  std::string out = "{\n";
  for (std::size_t i = 0; i < v.size(); ++i) {
    out += "    ";
    out += c_rgb(v[i]);
    out += i + 1 < v.size() ? ",\n" : "\n";
  }
  out += "}";
  return out;
}

// Text safe inside a C block comment: one line, no comment terminator.
std::string comment_text(std::string s) {
  for (char& ch : s)
    if (ch == '\n' || ch == '\r') ch = ' ';
  for (std::size_t at = s.find("*/"); at != std::string::npos; at = s.find("*/", at))
    s.replace(at, 2, "* /");
  return s;
}

}  // namespace

SeparableKernel make_separable_kernel(const RgbProfile& profile, int taps, double range_mm) {
  if (taps < 3 || taps % 2 == 0) {
    std::string msg = "make_separable_kernel: taps must be odd and >= 3, got ";
    msg += std::to_string(taps);
    throw std::invalid_argument(msg);
  }
  if (!std::isfinite(range_mm))
    throw std::invalid_argument("make_separable_kernel: range_mm must be finite");
  SeparableKernel k;
  k.total_reflectance = profile.total_reflectance();
  if (range_mm <= 0.0) {
    range_mm = 0.0;
    for (int c = 0; c < 3; ++c)
      range_mm = std::max(range_mm, tail_radius(profile.channel(c), kTailFraction));
  }
  k.range_mm = range_mm;

  // Offsets x = range·sign(t)·t², t = -1 + 2i/(taps-1) (Jimenez et al. 2015); the positive
  // half is computed and mirrored so the kernel is exactly symmetric with a tap at 0.
  const int half = (taps - 1) / 2;
  std::vector<double> positive(half + 1);
  for (int i = 0; i <= half; ++i) {
    const double t = static_cast<double>(i) / half;
    positive[i] = range_mm * t * t;
  }
  // Cell i >= 1 spans [b_{i-1}, b_i] with b_i the midpoint to the next tap and b_half = ∞;
  // the centre cell is [-b_0, b_0]. A cell's weight is the marginal's integral over it,
  // a difference of the edge response M; the telescoping sum is exactly the total.
  std::vector<Rgb> boundary_m(half + 1);  // M(b_i), with M(∞) = 0 last
  for (int i = 0; i < half; ++i)
    boundary_m[i] = edge_response(profile, 0.5 * (positive[i] + positive[i + 1]));
  boundary_m[half] = Rgb{};
  std::vector<Rgb> weight(half + 1);
  for (int c = 0; c < 3; ++c) {
    const double T = k.total_reflectance[c];
    const double inv = T > 0.0 ? 1.0 / T : 0.0;
    weight[0][c] = (T - 2.0 * boundary_m[0][c]) * inv;
    for (int i = 1; i <= half; ++i) weight[i][c] = (boundary_m[i - 1][c] - boundary_m[i][c]) * inv;
  }
  k.offsets_mm.resize(taps);
  k.weights.resize(taps);
  for (int i = 0; i <= half; ++i) {
    k.offsets_mm[half + i] = positive[i];
    k.offsets_mm[half - i] = -positive[i];
    k.weights[half + i] = weight[i];
    k.weights[half - i] = weight[i];
  }
  return k;
}

std::string kernel_to_json(const GaussianFit& fit, const KernelInfo& info,
                           const SeparableKernel* separable) {
  std::string out = "{\n";
  auto field = [&](const char* indent, const char* key, const std::string& value, bool last) {
    out += indent;
    out += '"';
    out += key;
    out += "\": ";
    out += value;
    out += last ? "\n" : ",\n";
  };
  field("  ", "model", json_string(info.model), false);
  field("  ", "medium", json_string(info.medium), false);
  field("  ", "variances_mm2", json_list(fit.variances_mm2), false);
  field("  ", "weights", json_rgb_list(fit.weights, "  "), false);
  field("  ", "total_reflectance", json_rgb(fit.total_reflectance), false);
  field("  ", "relative_error", json_rgb(fit.relative_error), separable == nullptr);
  if (separable) {
    out += "  \"separable\": {\n";
    field("    ", "offsets_mm", json_list(separable->offsets_mm), false);
    field("    ", "weights", json_rgb_list(separable->weights, "    "), false);
    field("    ", "total_reflectance", json_rgb(separable->total_reflectance), true);
    out += "  }\n";
  }
  out += "}\n";
  return out;
}

std::string kernel_to_c_header(const GaussianFit& fit, const KernelInfo& info,
                               const SeparableKernel* separable, const std::string& prefix) {
  const bool identifier =
      !prefix.empty() && !std::isdigit(static_cast<unsigned char>(prefix[0])) &&
      std::all_of(prefix.begin(), prefix.end(),
                  [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
  if (!identifier) {
    std::string msg = "kernel_to_c_header: prefix \"";
    msg += prefix;
    msg += "\" is not a C identifier";
    throw std::invalid_argument(msg);
  }
  std::string upper = prefix;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  const std::size_t n = fit.variances_mm2.size();
  const Rgb& e = fit.relative_error;
  char err[120];
  std::snprintf(err, sizeof err, "%.3e %.3e %.3e", e[0], e[1], e[2]);

  const std::string& p = prefix;
  std::string h;
  auto line = [&h](std::initializer_list<std::string_view> parts) {
    for (const std::string_view part : parts) h += part;
    h += '\n';
  };
  line({"/* Subsurface-scattering kernel, generated by sss-fit. Do not edit."});
  line({" *"});
  line({" * model:  ", comment_text(info.model)});
  line({" * medium: ", comment_text(info.medium)});
  line({" * fit error (R G B): ", err});
  line({" *   relative L2 error of r*R(r) over r: ||r (R - fit)|| / ||r R||."});
  line({" *"});
  line({" * Units: radii in mm, variances in mm^2, R(r) in mm^-2 (exitant flux per unit area"});
  line({" * per unit power entering the surface)."});
  line({" *"});
  line({" * Use: R_c(r) = sum_i ", p, "_weights[i][c] * G(", p, "_variances_mm2[i], r)"});
  line({" *      with G(v, r) = exp(-r*r / (2*v)) / (2*pi*v), a 2D Gaussian of unit integral;"});
  line({" *      sum_i ", p, "_weights[i][c] = ", p, "_total_reflectance[c]."});
  if (separable) {
    line({" * Separable: blur with the taps ", p, "_separable_weights[k][c] at offsets"});
    line({" *      ", p, "_separable_offsets_mm[k] horizontally, then vertically, then"});
    line({" *      multiply by ", p, "_separable_total_reflectance[c]. Each channel's"});
    line({" *      weights sum to 1; the result is exact for light that varies along one axis."});
  }
  line({" */"});
  line({"#ifndef ", upper, "_H"});
  line({"#define ", upper, "_H"});
  line({});
  line({"#define ", upper, "_COUNT ", std::to_string(n)});
  line({});
  line({"static const float ", p, "_variances_mm2[", upper, "_COUNT] = ", c_list(fit.variances_mm2), ";"});
  line({"static const float ", p, "_weights[", upper, "_COUNT][3] = ", c_rgb_list(fit.weights), ";"});
  line({"static const float ", p, "_total_reflectance[3] = ", c_rgb(fit.total_reflectance), ";"});
  line({"static const float ", p, "_relative_error[3] = ", c_rgb(fit.relative_error), ";"});
  if (separable) {
    line({});
    line({"#define ", upper, "_SEPARABLE_TAPS ", std::to_string(separable->offsets_mm.size())});
    line({});
    line({"static const float ", p, "_separable_offsets_mm[", upper, "_SEPARABLE_TAPS] = ",
          c_list(separable->offsets_mm), ";"});
    line({"static const float ", p, "_separable_weights[", upper, "_SEPARABLE_TAPS][3] = ",
          c_rgb_list(separable->weights), ";"});
    line({"static const float ", p, "_separable_total_reflectance[3] = ",
          c_rgb(separable->total_reflectance), ";"});
  }
  line({});
  line({"#endif /* ", upper, "_H */"});
  return h;
}

}  // namespace sss::profiles
