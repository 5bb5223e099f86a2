#include "scene/Environment.h"

#include "image/Image.h"
#include "scene/SplitSum.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace sss::scene {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Ramamoorthi & Hanrahan 2001, eq. 8: the clamped cosine's coefficients per band.
constexpr std::array<double, 9> kCosineBand = {kPi, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0, 2.0 * kPi / 3.0,
                                               kPi / 4.0, kPi / 4.0, kPi / 4.0, kPi / 4.0, kPi / 4.0};

bool finite_non_negative(float v) { return std::isfinite(v) && v >= 0.0f; }

void check_intensity(float intensity, const std::string& source) {
  if (!finite_non_negative(intensity)) {
    std::ostringstream s;
    s << source << ": the environment's intensity must be a finite number >= 0, got " << intensity;
    throw std::invalid_argument(s.str());
  }
}

// The direction of image coordinates (u, v) in [0, 1]^2 (the header's convention).
glm::vec3 direction_at(double u, double v) {
  const double theta = kPi * v, psi = 2.0 * kPi * (u - 0.5);
  return glm::vec3(float(std::sin(theta) * std::sin(psi)), float(std::cos(theta)),
                   float(-std::sin(theta) * std::cos(psi)));
}

}  // namespace

std::array<float, 9> sh_basis(const glm::vec3& d) {
  const float x = d.x, y = d.y, z = d.z;
  return {0.282095f,
          0.488603f * y,
          0.488603f * z,
          0.488603f * x,
          1.092548f * x * y,
          1.092548f * y * z,
          0.315392f * (3.0f * z * z - 1.0f),
          1.092548f * x * z,
          0.546274f * (x * x - y * y)};
}

glm::vec3 Environment::radiance(const glm::vec3& d) const {
  if (uniform()) return colour;
  return equirect_bilinear(image.data(), width, height, d);
}

glm::vec3 Environment::specular_radiance(const glm::vec3& r, float roughness) const {
  return specular_lookup(specular, r, roughness);
}

void Environment::scale(float k) {
  colour *= k;
  for (glm::vec3& p : image) p *= k;
  for (glm::vec3& c : irradiance_sh) c *= k;
  for (glm::vec3& p : specular) p *= k;
}

glm::vec3 Environment::irradiance(const glm::vec3& n) const {
  const std::array<float, 9> y = sh_basis(n);
  glm::vec3 e(0.0f);
  for (int k = 0; k < 9; ++k) e += irradiance_sh[k] * y[k];
  return glm::max(e, glm::vec3(0.0f));
}

Environment uniform_environment(const glm::vec3& radiance, float intensity) {
  std::ostringstream name;
  name << radiance.x << ',' << radiance.y << ',' << radiance.z;
  check_intensity(intensity, name.str());
  for (int c = 0; c < 3; ++c)
    if (!finite_non_negative(radiance[c])) {
      std::ostringstream s;
      s << "the environment's colour " << name.str() << ": each component must be a finite number >= 0";
      throw std::invalid_argument(s.str());
    }
  Environment e;
  e.source = name.str();
  e.colour = radiance * intensity;
  // Only Y_00 = 1 / sqrt(4 pi): L_00 = L sqrt(4 pi), E = A_0 L_00 Y_00 = pi L.
  e.irradiance_sh[0] = e.colour * float(kPi * std::sqrt(4.0 * kPi));
  // Every lobe average of a constant is the constant.
  e.specular.assign(std::size_t(kSpecularWidth) * kSpecularHeight * kSpecularLevels, e.colour);
  return e;
}

namespace {

// Each row's solid-angle weight, sin(theta) at its centre.
std::vector<double> row_weights(int height) {
  std::vector<double> row_weight(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) row_weight[std::size_t(y)] = std::sin(kPi * (y + 0.5) / height);
  return row_weight;
}

// L_k = sum over pixels of L Y_k dOmega, dOmega proportional to sin(theta) at the row's
// centre, scaled so the weights sum to 4 pi (a uniform image is then exact).
std::array<glm::dvec3, 9> radiance_sh(const Environment& e, const std::vector<double>& row_weight) {
  const int width = e.width, height = e.height;
  double total = 0.0;
  for (int y = 0; y < height; ++y) total += row_weight[std::size_t(y)] * width;
  std::array<glm::dvec3, 9> sum{};
  // direction_at, with each column's azimuth and each row's polar angle computed once.
  std::vector<double> sin_psi(static_cast<std::size_t>(width)), cos_psi(static_cast<std::size_t>(width));
  for (int x = 0; x < width; ++x) {
    const double psi = 2.0 * kPi * ((x + 0.5) / width - 0.5);
    sin_psi[std::size_t(x)] = std::sin(psi);
    cos_psi[std::size_t(x)] = std::cos(psi);
  }
  for (int y = 0; y < height; ++y) {
    const double theta = kPi * (y + 0.5) / height, st = std::sin(theta), ct = std::cos(theta);
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d(float(st * sin_psi[std::size_t(x)]), float(ct), float(-st * cos_psi[std::size_t(x)]));
      const std::array<float, 9> b = sh_basis(d);
      const glm::dvec3 l(e.image[std::size_t(y) * width + x]);
      const double w = row_weight[std::size_t(y)] * 4.0 * kPi / total;
      for (int k = 0; k < 9; ++k) sum[k] += l * (double(b[k]) * w);
    }
  }
  return sum;
}

// The radiance on the prefilter's grid: each grid texel the solid-angle mean of the
// pixels whose centres fall in it, when the image is at least as fine; else the image
// read bilinearly at the texel's centre.
std::vector<glm::vec3> prefilter_grid(const Environment& e, const std::vector<double>& row_weight) {
  const int width = e.width, height = e.height;
  const int gw = kSpecularWidth, gh = kSpecularHeight;
  std::vector<glm::vec3> grid(std::size_t(gw) * gh);
  if (width >= gw && height >= gh) {
    std::vector<glm::dvec3> acc(grid.size(), glm::dvec3(0.0));
    std::vector<double> weight(grid.size(), 0.0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        // The cell that holds the pixel's centre.
        const std::size_t cell =
            std::size_t(((2 * y + 1) * gh) / (2 * height)) * gw + std::size_t(((2 * x + 1) * gw) / (2 * width));
        acc[cell] += glm::dvec3(e.image[std::size_t(y) * width + x]) * row_weight[std::size_t(y)];
        weight[cell] += row_weight[std::size_t(y)];
      }
    for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = glm::vec3(acc[i] / std::max(weight[i], 1e-300));
  } else {
    for (int y = 0; y < gh; ++y)
      for (int x = 0; x < gw; ++x)
        grid[std::size_t(y) * gw + x] = e.radiance(direction_at((x + 0.5) / gw, (y + 0.5) / gh));
  }
  return grid;
}

}  // namespace

Environment image_environment(const std::string& source, int width, int height,
                              const std::vector<float>& rgba, float intensity) {
  check_intensity(intensity, source);
  if (width < 2 || height < 1 || rgba.size() != std::size_t(width) * height * 4) {
    std::ostringstream s;
    s << source << ": an environment image needs at least 2 x 1 pixels, got " << width << " x " << height;
    throw std::invalid_argument(s.str());
  }
  Environment e;
  e.source = source;
  e.width = width;
  e.height = height;
  e.image.resize(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float* p = &rgba[(std::size_t(y) * width + x) * 4];
      for (int c = 0; c < 3; ++c)
        if (!finite_non_negative(p[c])) {
          std::ostringstream s;
          s << source << ": pixel (" << x << ", " << y << ") channel " << "RGB"[c]
            << " must be a finite radiance >= 0, got " << p[c];
          throw std::invalid_argument(s.str());
        }
      e.image[std::size_t(y) * width + x] = glm::vec3(p[0], p[1], p[2]) * intensity;
    }
  const std::vector<double> row_weight = row_weights(height);
  const std::array<glm::dvec3, 9> sum = radiance_sh(e, row_weight);
  for (int k = 0; k < 9; ++k) e.irradiance_sh[k] = glm::vec3(sum[k] * kCosineBand[k]);
  e.specular = prefilter_levels(prefilter_grid(e, row_weight));
  return e;
}

Environment load_environment(const std::string& spec, float intensity) {
  // R,G,B: three numbers and two commas, nothing else.
  if (spec.find(',') != std::string::npos) {
    glm::vec3 rgb(0.0f);
    std::istringstream in(spec);
    char comma1 = 0, comma2 = 0;
    if (!(in >> rgb.x >> comma1 >> rgb.y >> comma2 >> rgb.z) || comma1 != ',' || comma2 != ',' ||
        !(in >> std::ws).eof())
      throw std::invalid_argument("the environment '" + spec +
                                  "' is neither R,G,B (three linear radiances) nor a file");
    return uniform_environment(rgb, intensity);
  }
  std::string lower = spec;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (lower.size() < 4 || lower.compare(lower.size() - 4, 4, ".exr") != 0)
    throw std::invalid_argument(spec + ": an environment image must be OpenEXR (.exr, linear radiance)");
  auto read = image::read_image(spec);
  if (const auto* error = std::get_if<image::ImageError>(&read)) throw std::invalid_argument(error->what());
  const image::Image& img = std::get<image::Image>(read);
  return image_environment(spec, img.width, img.height, img.rgba, intensity);
}

}  // namespace sss::scene
