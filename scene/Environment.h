// Environment light (issue 20 part 3): radiance arriving from infinitely far away in
// every direction, either one colour (a uniform sky) or an equirectangular HDR image
// (OpenEXR), times an intensity. Linear RGB radiance, in the units of the lights'
// irradiance (a uniform environment of radiance L gives an unoccluded surface
// E = pi L, so L = 1 matches a directional light of E = pi at normal incidence).
//
// Equirectangular convention (glTF's frame, +Y up): the direction d maps to
// u = 1/2 + atan2(d.x, -d.z) / (2 pi) (the image's centre column looks down -Z, the glTF
// camera's default view), v = acos(d.y) / pi (the top row is straight up), pixels at
// ((u, v) x size - 1/2), bilinear, wrapping in u.
//
// Diffuse irradiance on the GPU: the environment projected onto the 9 real spherical
// harmonics of bands 0..2 and convolved with the clamped cosine (Ramamoorthi & Hanrahan
// 2001, "An Efficient Representation for Irradiance Environment Maps": A0 = pi,
// A1 = 2 pi / 3, A2 = pi / 4), exact for a uniform environment and for any linear one,
// with a mean error of a few per cent for a typical HDRI and ringing (clamped at 0) behind
// a small bright sun.
//
// Specular light from it: the split sum (SplitSum.h), from `specular`, the radiance
// averaged over the GGX lobe at kSpecularLevels roughnesses.
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <string>
#include <vector>

namespace sss::scene {

struct Environment {
  std::string source;  // "R,G,B" or the file, for messages and stats
  glm::vec3 colour{0.0f};  // the uniform radiance (image empty), intensity applied
  int width = 0, height = 0;
  std::vector<glm::vec3> image;  // row-major, top row first, intensity applied
  // E(n) = sum_k sh[k] Y_k(n): the irradiance's coefficients (radiance coefficients x A_l),
  // in the order of sh_basis().
  std::array<glm::vec3, 9> irradiance_sh{};
  // The prefiltered radiance: kSpecularLevels layers of kSpecularWidth x kSpecularHeight
  // (SplitSum.h), intensity applied; what the GPU samples for specular light.
  std::vector<glm::vec3> specular;

  bool uniform() const { return image.empty(); }
  // The radiance arriving from direction d (unit, pointing away from the surface).
  glm::vec3 radiance(const glm::vec3& d) const;
  // The irradiance of a surface of unit normal n that sees the whole sphere above it,
  // from the spherical harmonics (what the GPU evaluates), clamped at 0.
  glm::vec3 irradiance(const glm::vec3& n) const;
  // The prefiltered radiance around the mirror direction r (unit) at perceptual roughness
  // `roughness` (scene::specular_lookup of `specular`, as the GPU reads it).
  glm::vec3 specular_radiance(const glm::vec3& r, float roughness) const;
  // Every radiance it holds (image, colour, harmonics, prefiltered levels) times k >= 0:
  // the viewer's live scale, without prefiltering again.
  void scale(float k);
};

// The 9 real spherical harmonics Y_00, Y_1-1, Y_10, Y_11, Y_2-2, Y_2-1, Y_20, Y_21, Y_22
// at unit direction d (Ramamoorthi & Hanrahan 2001, eq. 3; x, y, z world axes).
std::array<float, 9> sh_basis(const glm::vec3& d);

// A uniform environment; throws std::invalid_argument for a negative or non-finite
// component or intensity.
Environment uniform_environment(const glm::vec3& radiance, float intensity = 1.0f);
// An equirectangular image (linear RGB, 4 floats per pixel as image::Image holds them);
// throws std::invalid_argument naming `source` for a size under 2 x 1 or a negative or
// non-finite pixel.
Environment image_environment(const std::string& source, int width, int height,
                              const std::vector<float>& rgba, float intensity = 1.0f);
// "R,G,B" (linear radiance, each >= 0) or an image file (OpenEXR: linear; PNG is refused,
// its 8 bits hold no sky). Throws std::invalid_argument with a message that names the
// file or the value.
Environment load_environment(const std::string& spec, float intensity = 1.0f);

}  // namespace sss::scene
