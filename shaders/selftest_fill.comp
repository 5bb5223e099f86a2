// Self-test of the shader pipeline (tests/vk): values[i] = scale * i + offset.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/config.h"
#include "shared/selftest.h"

layout(local_size_x = SSS_WORKGROUP_1D) in;

layout(set = 0, binding = 0, std430) writeonly buffer Values {
  float values[];
};

layout(push_constant) uniform Push {
  SelftestFillParams params;
};

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  values[i] = params.scale * float(i) + params.offset;
}
