// Specular light from the environment by the split-sum approximation (Karis 2013, "Real
// Shading in Unreal Engine 4", SIGGRAPH course notes): the GGX lobe's integral against the
// environment,
//   S(V) = integral of L(l) f(V, l) (n.l) dl,
// f the project's lobe (GGX D, Smith height-correlated visibility, Schlick Fresnel: the
// one shading.glsl and reference/Shading.cpp evaluate for lights), is split into
//   S ~ Lp(R, r) x (F0 A(n.v, r) + B(n.v, r)),
// R the mirror direction and r the perceptual roughness (alpha = r^2, floored at 1e-3 as
// the lights' lobe is):
//   * A, B: the lobe's directional albedo under a white sky, split by Schlick's weight
//     Fc = (1 - v.h)^5 (F = F0 (1 - Fc) + Fc): A = E[f/F (1 - Fc) n.l], B = E[f/F Fc n.l].
//     Tabulated once (dfg_table) over n.v and r at texel centres, looked up bilinearly.
//   * Lp: the environment's radiance averaged over the lobe around R with N = V = R,
//     weighted by D(h) (n.l) (Karis' "prefiltered environment map"), at kSpecularLevels
//     roughnesses (Environment::specular).
// Exact for a uniform sky (Lp = L); for others the lobe's shape at grazing angles (the
// N = V = R assumption) is the approximation.
//
// The GPU reads both tables with texelFetch and does the same bilinear arithmetic as
// dfg_lookup and specular_lookup here (shaders/shared/shading.glsl), so the reference's
// GPU-lighting mode (reference/Shading.cpp) reproduces the frame's specular.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace sss::scene {

// The DFG table: kDfgSize x kDfgSize texels (A, B); column i is n.v = (i + 1/2) / kDfgSize,
// row j is r = (j + 1/2) / kDfgSize.
inline constexpr int kDfgSize = 32;
// Low-discrepancy points per texel (Hammersley).
inline constexpr int kDfgSamples = 4096;
const std::vector<glm::vec2>& dfg_table();
// Bilinear between texel centres, clamped at the table's edges (as the GPU reads it).
glm::vec2 dfg_lookup(float n_dot_v, float roughness);

// One (n.v, r) entry by importance sampling GGX's normals (Walter et al. 2007, eq. 35:
// tan^2 theta_h = alpha^2 u / (1 - u)), `samples` Hammersley points. `spread` is the
// standard deviation of one sample's (A, B) weights: a bound on the points' error is
// about spread / sqrt(samples) (random points; low-discrepancy ones do better).
struct DfgEntry {
  glm::dvec2 ab{0.0};
  glm::dvec2 spread{0.0};
};
DfgEntry dfg_integrate(double n_dot_v, double roughness, int samples);

// The GGX alpha of a perceptual roughness, as the lights' lobe takes it.
double ggx_alpha(double roughness);
// Smith's height-correlated visibility G2 / (4 n.l n.v) (Heitz 2014) of GGX with alpha^2 = a2:
// the lights' lobe is D vis F.
double smith_visibility(double n_dot_l, double n_dot_v, double a2);
// cos(theta_h) of a GGX normal drawn with density D(h) n.h from u in [0, 1) (Walter et al.
// 2007, eq. 35: tan^2 theta_h = a2 u / (1 - u)); its azimuth is uniform.
double ggx_normal_cosine(double u, double a2);

// The prefiltered levels: level k has roughness k / (kSpecularLevels - 1) and holds the
// lobe-averaged radiance at (kSpecularWidth >> k) x (kSpecularHeight >> k) directions (no
// fewer than 32 x 16)
// (equirectangular, Environment.h's convention), resampled bilinearly to
// kSpecularWidth x kSpecularHeight so the GPU reads the levels as layers of one image.
inline constexpr int kSpecularLevels = 6;
inline constexpr int kSpecularWidth = 128;
inline constexpr int kSpecularHeight = 64;

// Bilinear lookup of an equirectangular image (w x h, rows top first) in direction d
// (unit): u wraps, v clamps to the first and last rows' centres.
glm::vec3 equirect_bilinear(const glm::vec3* image, int width, int height, const glm::vec3& d);

// Lp(R, r) from the levels (kSpecularLevels layers of kSpecularWidth x kSpecularHeight):
// the two levels around r x (kSpecularLevels - 1), each bilinear, mixed linearly.
glm::vec3 specular_lookup(const std::vector<glm::vec3>& levels, const glm::vec3& r, float roughness);

// The levels of an environment given as its radiance on a kSpecularWidth x
// kSpecularHeight grid (each texel the radiance averaged over its solid angle).
std::vector<glm::vec3> prefilter_levels(const std::vector<glm::vec3>& grid);

}  // namespace sss::scene
