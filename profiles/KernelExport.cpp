#include "profiles/KernelExport.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace sss::profiles {

namespace {

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

}  // namespace

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
  field("  ", "relative_error", json_rgb(fit.relative_error), false);
  // The standard deviation (mm) of the blur under which relative_error compares the
  // kernel with the profile (0: unblurred; FitTarget::prefilter_variance_mm2).
  field("  ", "resolution_mm", number(std::sqrt(fit.prefilter_variance_mm2)),
        separable == nullptr);
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

}  // namespace sss::profiles
