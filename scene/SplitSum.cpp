#include "scene/SplitSum.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sss::scene {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kMinLevelWidth = 32;

// Van der Corput's radical inverse in base 2 (the Hammersley set's second coordinate).
double radical_inverse(std::uint32_t i) {
  i = (i << 16u) | (i >> 16u);
  i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
  i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
  i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
  i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
  return double(i) * (1.0 / 4294967296.0);
}

// Direction of equirectangular coordinates (u, v) (Environment.h's convention).
glm::dvec3 direction_at(double u, double v) {
  const double theta = kPi * v, psi = 2.0 * kPi * (u - 0.5);
  return {std::sin(theta) * std::sin(psi), std::cos(theta), -std::sin(theta) * std::cos(psi)};
}

// A w x h equirectangular grid averaged 2 x 2 into (w/2) x (h/2), each texel weighted by
// its solid angle (sin theta at its centre).
std::vector<glm::vec3> halve(const std::vector<glm::vec3>& g, int w, int h) {
  std::vector<glm::vec3> out(std::size_t(w / 2) * (h / 2));
  for (int y = 0; y < h / 2; ++y)
    for (int x = 0; x < w / 2; ++x) {
      glm::dvec3 sum(0.0);
      double weight = 0.0;
      for (int dy = 0; dy < 2; ++dy) {
        const double s = std::sin(kPi * (2 * y + dy + 0.5) / h);
        for (int dx = 0; dx < 2; ++dx) sum += glm::dvec3(g[std::size_t(2 * y + dy) * w + 2 * x + dx]) * s;
        weight += 2.0 * s;
      }
      out[std::size_t(y) * (w / 2) + x] = glm::vec3(sum / weight);
    }
  return out;
}

}  // namespace

double ggx_alpha(double roughness) { return std::max(roughness * roughness, 1e-3); }

double smith_visibility(double nl, double nv, double a2) {
  return 0.5 / (nl * std::sqrt(nv * nv * (1.0 - a2) + a2) + nv * std::sqrt(nl * nl * (1.0 - a2) + a2));
}

double ggx_normal_cosine(double u, double a2) {
  return 1.0 / std::sqrt(1.0 + a2 * u / std::max(1.0 - u, 1e-300));
}

DfgEntry dfg_integrate(double n_dot_v, double roughness, int samples) {
  const double nv = std::clamp(n_dot_v, 1e-4, 1.0);
  const double alpha = ggx_alpha(roughness), a2 = alpha * alpha;
  const glm::dvec3 v(std::sqrt(1.0 - nv * nv), 0.0, nv);  // n = +z
  glm::dvec2 sum(0.0), sum2(0.0);
  for (int i = 0; i < samples; ++i) {
    const double u1 = (i + 0.5) / samples, u2 = radical_inverse(std::uint32_t(i));
    const double cos_h = ggx_normal_cosine(u1, a2), sin_h = std::sqrt(std::max(0.0, 1.0 - cos_h * cos_h));
    const double phi = 2.0 * kPi * u2;
    const glm::dvec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
    const double vh = glm::dot(v, h);
    const glm::dvec3 l = 2.0 * vh * h - v;
    glm::dvec2 w(0.0);
    if (l.z > 0.0 && vh > 0.0) {
      // f n.l / pdf(l), pdf(l) = D (n.h) / (4 v.h): D cancels.
      const double weight = smith_visibility(l.z, nv, a2) * 4.0 * vh * l.z / cos_h;
      const double fc = std::pow(1.0 - vh, 5.0);
      w = {weight * (1.0 - fc), weight * fc};
    }
    sum += w;
    sum2 += w * w;
  }
  DfgEntry e;
  e.ab = sum / double(samples);
  e.spread = glm::sqrt(glm::max(sum2 / double(samples) - e.ab * e.ab, glm::dvec2(0.0)));
  return e;
}

const std::vector<glm::vec2>& dfg_table() {
  static const std::vector<glm::vec2> table = [] {
    std::vector<glm::vec2> t(std::size_t(kDfgSize) * kDfgSize);
    for (int j = 0; j < kDfgSize; ++j)
      for (int i = 0; i < kDfgSize; ++i)
        t[std::size_t(j) * kDfgSize + i] =
            glm::vec2(dfg_integrate((i + 0.5) / kDfgSize, (j + 0.5) / kDfgSize, kDfgSamples).ab);
    return t;
  }();
  return table;
}

glm::vec2 dfg_lookup(float n_dot_v, float roughness) {
  const std::vector<glm::vec2>& t = dfg_table();
  const float x = std::clamp(n_dot_v * kDfgSize - 0.5f, 0.0f, float(kDfgSize - 1));
  const float y = std::clamp(roughness * kDfgSize - 0.5f, 0.0f, float(kDfgSize - 1));
  const int x0 = std::min(int(x), kDfgSize - 2), y0 = std::min(int(y), kDfgSize - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [&](int i, int j) { return t[std::size_t(j) * kDfgSize + i]; };
  return (at(x0, y0) * (1.0f - fx) + at(x0 + 1, y0) * fx) * (1.0f - fy) +
         (at(x0, y0 + 1) * (1.0f - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

glm::vec3 equirect_bilinear(const glm::vec3* image, int width, int height, const glm::vec3& d) {
  const glm::vec3 n = glm::normalize(d);
  // Straight up or down, u = 1/2 (GLSL's atan(0, 0) is undefined; atan2 would give 0 or pi).
  const double u = (n.x == 0.0f && n.z == 0.0f) ? 0.5 : 0.5 + std::atan2(double(n.x), double(-n.z)) / (2.0 * kPi);
  const double v = std::acos(std::clamp(double(n.y), -1.0, 1.0)) / kPi;
  const double fx = u * width - 0.5, fy = std::clamp(v * height - 0.5, 0.0, double(height - 1));
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float tx = float(fx - x0), ty = float(fy - y0);
  const auto at = [&](int x, int y) {
    x = ((x % width) + width) % width;  // wraps in u
    y = std::clamp(y, 0, height - 1);
    return image[std::size_t(y) * width + x];
  };
  const glm::vec3 top = at(x0, y0) * (1.0f - tx) + at(x0 + 1, y0) * tx;
  const glm::vec3 bottom = at(x0, y0 + 1) * (1.0f - tx) + at(x0 + 1, y0 + 1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

glm::vec3 specular_lookup(const std::vector<glm::vec3>& levels, const glm::vec3& r, float roughness) {
  const std::size_t layer = std::size_t(kSpecularWidth) * kSpecularHeight;
  const float f = std::clamp(roughness, 0.0f, 1.0f) * float(kSpecularLevels - 1);
  const int k0 = std::min(int(f), kSpecularLevels - 2);
  const float t = f - float(k0);
  const glm::vec3 a = equirect_bilinear(levels.data() + layer * k0, kSpecularWidth, kSpecularHeight, r);
  const glm::vec3 b = equirect_bilinear(levels.data() + layer * (k0 + 1), kSpecularWidth, kSpecularHeight, r);
  return a * (1.0f - t) + b * t;
}

std::vector<glm::vec3> prefilter_levels(const std::vector<glm::vec3>& grid) {
  const int W = kSpecularWidth, H = kSpecularHeight;
  const std::size_t layer = std::size_t(W) * H;
  std::vector<glm::vec3> levels(layer * kSpecularLevels);
  std::copy(grid.begin(), grid.end(), levels.begin());  // level 0: the mirror (alpha 1e-3)
  // The quadrature for level k runs over the radiance at level k - 1's resolution (each
  // texel its solid angle's mean), which the wider lobe of level k does not resolve finer.
  std::vector<glm::vec3> source = grid;
  int sw = W, sh = H;
  for (int k = 1; k < kSpecularLevels; ++k) {
    const double alpha = ggx_alpha(double(k) / (kSpecularLevels - 1)), a2 = alpha * alpha;
    // The source's directions and solid angles.
    std::vector<glm::dvec3> dirs(std::size_t(sw) * sh);
    std::vector<double> solid(static_cast<std::size_t>(sh));
    for (int y = 0; y < sh; ++y) {
      solid[std::size_t(y)] = std::sin(kPi * (y + 0.5) / sh);
      for (int x = 0; x < sw; ++x) dirs[std::size_t(y) * sw + x] = direction_at((x + 0.5) / sw, (y + 0.5) / sh);
    }
    // Each level at (W >> k) x (H >> k), but no coarser than kMinLevelWidth wide: a 4 x 2
    // grid would put a bilinear error of 10% of a linear sky's gradient into the roughest
    // lobe (tests/scene/test_split_sum.cpp).
    const int ow = std::max(W >> k, kMinLevelWidth), oh = std::max(H >> k, kMinLevelWidth / 2);
    std::vector<glm::vec3> out(std::size_t(ow) * oh);
    for (int oy = 0; oy < oh; ++oy)
      for (int ox = 0; ox < ow; ++ox) {
        const glm::dvec3 r = direction_at((ox + 0.5) / ow, (oy + 0.5) / oh);
        glm::dvec3 sum(0.0);
        double weight = 0.0;
        for (int y = 0; y < sh; ++y)
          for (int x = 0; x < sw; ++x) {
            const glm::dvec3& l = dirs[std::size_t(y) * sw + x];
            const double nl = glm::dot(r, l);
            if (nl <= 0.0) continue;
            // n = v = r: n.h = sqrt((1 + n.l) / 2) for h = normalize(l + r).
            const double nh2 = 0.5 * (1.0 + nl);
            const double dd = nh2 * (a2 - 1.0) + 1.0;
            const double w = nl * solid[std::size_t(y)] / (dd * dd);  // D up to a2 / pi
            sum += glm::dvec3(source[std::size_t(y) * sw + x]) * w;
            weight += w;
          }
        out[std::size_t(oy) * ow + ox] = glm::vec3(weight > 0.0 ? sum / weight : glm::dvec3(0.0));
      }
    // Resampled to W x H with the lookup's own bilinear rule.
    glm::vec3* dst = levels.data() + layer * k;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x)
        dst[std::size_t(y) * W + x] =
            equirect_bilinear(out.data(), ow, oh, glm::vec3(direction_at((x + 0.5) / W, (y + 0.5) / H)));
    if (sw > kMinLevelWidth) {
      source = halve(source, sw, sh);
      sw /= 2;
      sh /= 2;
    }
  }
  return levels;
}

}  // namespace sss::scene
