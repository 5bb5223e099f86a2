// scene::Environment (issue 20 part 3, environment light): the spherical-harmonic
// irradiance against closed forms, the equirectangular convention, and bad input.
#include "scene/Environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss::scene {
namespace {

constexpr double kPi = 3.14159265358979323846;

// An equirectangular image whose pixel (x, y) holds f(direction at its centre), in the
// header's convention (u = 1/2 + atan2(x, -z) / 2 pi, v = acos(y) / pi).
template <class F>
std::vector<float> equirect(int w, int h, F f) {
  std::vector<float> rgba(std::size_t(w) * h * 4, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double theta = kPi * (y + 0.5) / h, psi = 2.0 * kPi * ((x + 0.5) / w - 0.5);
      const glm::vec3 d(float(std::sin(theta) * std::sin(psi)), float(std::cos(theta)),
                        float(-std::sin(theta) * std::cos(psi)));
      const glm::vec3 v = f(d);
      float* p = &rgba[(std::size_t(y) * w + x) * 4];
      p[0] = v.x;
      p[1] = v.y;
      p[2] = v.z;
    }
  return rgba;
}

const glm::vec3 kNormals[] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {0.6f, 0.0f, 0.8f}, {0.48f, 0.6f, -0.64f}};

TEST(Environment, AUniformSkyGivesPiLOnEveryNormal) {
  const Environment e = uniform_environment({0.5f, 1.0f, 2.0f}, 2.0f);
  for (const glm::vec3& n : kNormals) {
    const glm::vec3 E = e.irradiance(n);
    // Exact up to float: E = A_0 L_00 Y_00 = pi L.
    EXPECT_NEAR(E.x, kPi * 1.0, 1e-5);
    EXPECT_NEAR(E.y, kPi * 2.0, 1e-5);
    EXPECT_NEAR(E.z, kPi * 4.0, 1e-5);
  }
  EXPECT_EQ(e.radiance({0, 0, 1}), glm::vec3(1.0f, 2.0f, 4.0f));
}

// A linear sky L(w) = a + b w.y lies in bands 0 and 1, where the irradiance is exact:
// E(n) = pi a + (2 pi / 3) b n.y (the clamped cosine's band coefficients). The image
// samples it at pixel centres and the projection sums them with sin(theta) weights, a
// midpoint rule whose error falls as 1/H^2: about (pi / H)^2 / 24 of the integrand's
// scale, 2.5e-5 for H = 128. Tolerance 1e-4 of pi (a + |b|).
TEST(Environment, ALinearSkyIsExactInTheSphericalHarmonics) {
  const float a = 1.0f, b = 0.8f;
  const int w = 256, h = 128;
  const Environment e = image_environment("linear", w, h, equirect(w, h, [&](const glm::vec3& d) {
                                            return glm::vec3(a + b * d.y, a - b * d.y, a + b * d.x);
                                          }));
  const double tol = 1e-4 * kPi * (a + b);
  for (const glm::vec3& n : kNormals) {
    const glm::vec3 E = e.irradiance(n);
    EXPECT_NEAR(E.x, kPi * a + 2.0 * kPi / 3.0 * b * n.y, tol) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(E.y, kPi * a - 2.0 * kPi / 3.0 * b * n.y, tol);
    EXPECT_NEAR(E.z, kPi * a + 2.0 * kPi / 3.0 * b * n.x, tol);
  }
}

// Band 2: L = z^2 = 1/3 + (2/3) P_2(z), P_2(t) = (3 t^2 - 1) / 2, so the clamped cosine
// (A_0 = pi, A_2 = pi / 4 on each band) gives E(n) = pi / 3 + (pi / 4)(2 / 3) P_2(n.z)
// = pi / 3 + (pi / 12)(3 n.z^2 - 1). Same tolerance as above.
TEST(Environment, AQuadraticSkyIsExactInBandTwo) {
  const int w = 256, h = 128;
  const Environment e = image_environment("quadratic", w, h, equirect(w, h, [](const glm::vec3& d) {
                                            return glm::vec3(d.z * d.z);
                                          }));
  for (const glm::vec3& n : kNormals) {
    const double expected = kPi / 3.0 + kPi / 12.0 * (3.0 * n.z * n.z - 1.0);
    EXPECT_NEAR(e.irradiance(n).x, expected, 1e-4 * kPi) << n.x << " " << n.y << " " << n.z;
  }
}

// The convention: the top row is straight up, the centre column looks down -Z, and u
// grows towards +X (atan2(x, -z)): a column a quarter of the width right of the centre
// is +X.
TEST(Environment, EquirectangularConvention) {
  const int w = 64, h = 32;
  std::vector<float> rgba(std::size_t(w) * h * 4, 0.0f);
  const auto set = [&](int x, int y, float v) { rgba[(std::size_t(y) * w + x) * 4] = v; };
  for (int x = 0; x < w; ++x) set(x, 0, 5.0f);    // the top row
  for (int y = 8; y < 24; ++y) {
    set(w / 2 - 1, y, 3.0f), set(w / 2, y, 3.0f);  // the centre column
    set(3 * w / 4 - 1, y, 7.0f), set(3 * w / 4, y, 7.0f);  // a quarter to the right
  }
  const Environment e = image_environment("marks", w, h, rgba);
  EXPECT_NEAR(e.radiance({0, 1, 0}).x, 5.0f, 1e-5);
  EXPECT_NEAR(e.radiance({0, 0, -1}).x, 3.0f, 1e-5);
  EXPECT_NEAR(e.radiance({1, 0, 0}).x, 7.0f, 1e-5);
  EXPECT_NEAR(e.radiance({0, 0, 1}).x, 0.0f, 1e-5);   // behind: the seam, wrapped
  EXPECT_NEAR(e.radiance({-1, 0, 0}).x, 0.0f, 1e-5);
}

TEST(Environment, RefusesWhatIsNoSky) {
  const auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { uniform_environment({1.0f, -1.0f, 1.0f}); }).find("finite number >= 0"), std::string::npos);
  EXPECT_NE(message([] { uniform_environment({1.0f, NAN, 1.0f}); }).find("finite number >= 0"), std::string::npos);
  EXPECT_NE(message([] { uniform_environment({1.0f, 1.0f, 1.0f}, -2.0f); }).find("intensity"), std::string::npos);
  std::vector<float> one(4, 1.0f);
  EXPECT_NE(message([&] { image_environment("tiny.exr", 1, 1, one); }).find("tiny.exr: an environment image needs"),
            std::string::npos);
  std::vector<float> bad(2 * 1 * 4, 1.0f);
  bad[5] = -1.0f;
  EXPECT_NE(message([&] { image_environment("bad.exr", 2, 1, bad); }).find("bad.exr: pixel (1, 0) channel G"),
            std::string::npos);
  EXPECT_NE(message([] { load_environment("1,2"); }).find("neither R,G,B"), std::string::npos);
  EXPECT_NE(message([] { load_environment("1,2,3,4"); }).find("neither R,G,B"), std::string::npos);
  EXPECT_NE(message([] { load_environment("sky.png"); }).find("must be OpenEXR"), std::string::npos);
  EXPECT_NE(message([] { load_environment("/nonexistent/sky.exr"); }).find("/nonexistent/sky.exr"), std::string::npos);
}

}  // namespace
}  // namespace sss::scene
