// Push constants of the self-test shaders (tests/vk), declared once for C++ and GLSL:
// the struct below is valid in both languages, with std430/push-constant layout equal to
// the C++ layout because every member is a 4-byte scalar.
#ifndef SSS_SHADERS_SHARED_SELFTEST_H
#define SSS_SHADERS_SHARED_SELFTEST_H

#include "config.h"

#ifdef __cplusplus
namespace sss::shader {
#endif

// selftest_fill.comp writes values[i] = scale * float(i) + offset for i < count.
struct SelftestFillParams {
  uint count;
  float scale;
  float offset;
  uint pad;
};

#ifdef __cplusplus
static_assert(sizeof(SelftestFillParams) == 16);
}  // namespace sss::shader
#endif

#endif  // SSS_SHADERS_SHARED_SELFTEST_H
