// The constants that C++ and GLSL share (shaders/shared/config.h) agree with the
// libraries they mirror, at compile time.
#include "shaders/shared/config.h"

#include "profiles/GaussianFit.h"
#include "shaders/shared/selftest.h"

#include <gtest/gtest.h>

#include <cstddef>

static_assert(SSS_MAX_GAUSSIANS == sss::profiles::kMaxGaussians,
              "shaders/shared/config.h and profiles/GaussianFit.h disagree on the Gaussian count");
static_assert(sss::shader::kMaxGaussians == sss::profiles::kMaxGaussians);
static_assert(offsetof(sss::shader::SelftestFillParams, offset) == 8);

TEST(ShaderConfig, WorkgroupSizesAreSane) {
  EXPECT_EQ(sss::shader::kWorkgroup2DX * sss::shader::kWorkgroup2DY, 64u);
  EXPECT_EQ(sss::shader::kWorkgroup1D % 8, 0u);  // lavapipe's subgroup size
}
