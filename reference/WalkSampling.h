// The small routines of the volumetric random walk (RandomWalk.h), written here rather
// than shared with profiles/ so that the walk's validation against profiles' analog Monte
// Carlo and mc-table compares two codes, not one (issue 16):
//
// - WalkRng: a counter-based stream per (seed, pixel, sample): SplitMix64's finaliser
//   (Steele, Lea & Flood 2014; Vigna's constants) hashes the three numbers into the state
//   of a 64-bit PCG generator (O'Neill 2014, "PCG: a family of simple fast space-efficient
//   statistically good algorithms", XSH-RR output). A pixel's samples therefore never
//   depend on which thread, tile or machine draws them.
// - Henyey–Greenstein (1941) sampling by inverting its CDF, with the g -> 0 limit handled,
//   and its pdf per steradian.
// - The exact Fresnel reflectance of a smooth dielectric for unpolarised light (the mean
//   of the s and p amplitudes squared; Born & Wolf, Principles of Optics, §1.5) and
//   Snell refraction of a direction.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sss::reference::walk {

inline constexpr double kPi = 3.14159265358979323846;

inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

class WalkRng {
 public:
  WalkRng(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample) {
    const std::uint64_t a = mix64(seed + 0x9E3779B97F4A7C15ull);
    const std::uint64_t b = mix64(a ^ (pixel * 0xD1B54A32D192ED03ull + 0x632BE59BD9B4E019ull));
    state_ = mix64(b ^ (sample * 0x8CB92BA72F3D8DD7ull + 0x2545F4914F6CDD1Dull));
    inc_ = (mix64(b + sample) << 1) | 1u;  // odd: a full-period stream
    next_u32();
  }
  std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return double(((hi << 32) | lo) >> 11) * 0x1.0p-53;
  }

 private:
  std::uint64_t state_ = 0, inc_ = 1;
};

// Any unit vector t, b with (t, b, n) orthonormal (Duff et al. 2017, "Building an
// orthonormal basis, revisited", JCGT 6(1)).
inline void basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::dvec3(c, sign + n.y * n.y * a, -n.y);
}

// Henyey–Greenstein phase function per steradian at the cosine between the directions
// of travel before and after scattering.
inline double hg_pdf(double g, double cos_theta) {
  const double denom = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * kPi * denom * std::sqrt(denom));
}

// The cosine of a Henyey–Greenstein deflection for a uniform u in [0, 1).
inline double hg_sample_cos(double g, double u) {
  if (std::abs(g) < 1e-4) return 1.0 - 2.0 * u;  // the first-order error in g is below 1e-4
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

// A new direction of travel scattered from `w` (unit) by Henyey–Greenstein with g.
inline glm::dvec3 hg_sample(double g, const glm::dvec3& w, double u1, double u2) {
  const double c = hg_sample_cos(g, u1);
  const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
  const double phi = 2.0 * kPi * u2;
  glm::dvec3 t, b;
  basis(w, t, b);
  return glm::normalize(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + w * c);
}

// Reflectance of a smooth dielectric for unpolarised light arriving with cosine cos_i
// (> 0) from a medium of index n_i towards one of index n_t. Total internal reflection
// gives 1.
inline double fresnel(double cos_i, double n_i, double n_t) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double ratio = n_i / n_t;
  const double sin_t2 = ratio * ratio * (1.0 - cos_i * cos_i);
  if (sin_t2 >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
  const double rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

// Refracts the direction of travel `w` (unit) through a surface whose unit normal `n`
// points back against it (dot(w, n) < 0), from index n_i into n_t. False on total
// internal reflection.
inline bool refract(const glm::dvec3& w, const glm::dvec3& n, double n_i, double n_t, glm::dvec3& out) {
  const double ratio = n_i / n_t;
  const double cos_i = -glm::dot(w, n);
  const double sin_t2 = ratio * ratio * std::max(0.0, 1.0 - cos_i * cos_i);
  if (sin_t2 >= 1.0) return false;
  const double cos_t = std::sqrt(1.0 - sin_t2);
  out = glm::normalize(w * ratio + n * (ratio * cos_i - cos_t));
  return true;
}

inline glm::dvec3 reflect(const glm::dvec3& w, const glm::dvec3& n) { return w - 2.0 * glm::dot(w, n) * n; }

}  // namespace sss::reference::walk
