// Random numbers and the small sampling routines of the Monte Carlo random walk.
//
// - SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number
//   generators", OOPSLA; constants as in Vigna's public-domain description) seeds
//   - Xoshiro256ss, xoshiro256** (Blackman & Vigna 2018/2021, "Scrambled linear
//     pseudorandom number generators", ACM TOMS 47(4)): 256 bits of state, period
//     2^256 - 1, the recommended all-purpose 64-bit generator of that paper.
// - Streams: Xoshiro256ss(seed, stream) hashes both numbers through SplitMix64, so that
//   chunk k of a run with seed s always sees the same numbers, whatever thread runs it.
// - sample_hg_cos: the exact inversion of the Henyey–Greenstein CDF, rearranged so that
//   it is accurate to a few ε for every g in (-1, 1), g -> 0 and |g| -> 1 included.
// - sample_azimuth: cos φ, sin φ for uniform φ without trigonometric functions (von
//   Neumann 1951: a uniform point in the unit disc has a uniform angle; its doubled angle
//   is uniform too and needs no square root).
#pragma once

#include <algorithm>
#include <cstdint>

namespace sss::profiles {

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t state) : state_(state) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

class Xoshiro256ss {
 public:
  // One stream per (seed, stream) pair. The four state words come from SplitMix64, which
  // never yields four zero words from one sequence in practice (and we check anyway).
  explicit Xoshiro256ss(std::uint64_t seed, std::uint64_t stream = 0) {
    SplitMix64 outer(seed);
    // Mix the stream index through a second SplitMix64 so that nearby (seed, stream)
    // pairs start from unrelated states.
    SplitMix64 inner(outer.next() ^ SplitMix64(stream ^ 0xD1B54A32D192ED03ull).next());
    for (auto& w : s_) w = inner.next();
    if ((s_[0] | s_[1] | s_[2] | s_[3]) == 0) s_[0] = 1;  // the one forbidden state
  }

  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform in [0, 1) with 53 random bits (every representable multiple of 2^-53).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
};

// cos θ of the Henyey–Greenstein phase function p(cos θ) = (1 - g²) / (4π (1 + g² -
// 2g cos θ)^{3/2}) from one uniform ξ in [0, 1]. The textbook inversion (e.g. Jensen et
// al. 2001; Prahl's MCML notes) reads
//   cos θ = (1 + g² - ((1 - g²) / (1 + g a))²) / (2g),   a = 2ξ - 1,
// which cancels catastrophically as g -> 0 (relative error ~ε/g). Expanding it and
// dividing by 2g exactly gives the same function as
//   cos θ = a + (1 - a²) g (3/2 + g a - g²/2) / (1 + g a)².
// For g >= 0, with 1 - a² = 4ξ(1 - ξ), 1 + g a = (1 - g) + 2gξ and
// 3/2 + g a - g²/2 = (1 - g)(3 + g)/2 + 2gξ, every term is >= 0: no cancellation for
// any g in [0, 1), cos θ = a exactly at g = 0, and ±1 exactly at ξ = 1, 0. Negative g use
// the symmetry cos θ(g, ξ) = -cos θ(-g, 1 - ξ) (1 - ξ is exact for ξ = k 2^-53).
inline double sample_hg_cos(double g, double xi) {
  if (g < 0.0) return -sample_hg_cos(-g, 1.0 - xi);
  const double a = 2.0 * xi - 1.0;
  const double one_minus_g = 1.0 - g;
  const double s = one_minus_g + 2.0 * g * xi;
  const double q = 0.5 * one_minus_g * (3.0 + g) + 2.0 * g * xi;
  return std::clamp(a + 4.0 * xi * (1.0 - xi) * g * q / (s * s), -1.0, 1.0);
}

// (cos φ, sin φ) for φ uniform in [0, 2π): rejection-sample (x, y) in the unit disc
// (acceptance π/4) and return the doubled angle, ((x² - y²), 2xy) / (x² + y²).
template <class Rng>
inline void sample_azimuth(Rng& rng, double& cos_phi, double& sin_phi) {
  for (;;) {
    const double x = 2.0 * rng.uniform() - 1.0;
    const double y = 2.0 * rng.uniform() - 1.0;
    const double r2 = x * x + y * y;
    if (r2 > 1.0 || r2 < 1e-300) continue;
    const double inv = 1.0 / r2;
    cos_phi = (x * x - y * y) * inv;
    sin_phi = 2.0 * x * y * inv;
    return;
  }
}

}  // namespace sss::profiles
