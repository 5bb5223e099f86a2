// Self-test of image descriptors (tests/vk): dst = texture(src, nearest) * gain, with a
// separate sampled image, sampler, storage image and uniform buffer.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/config.h"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform texture2D src;
layout(set = 0, binding = 1) uniform sampler nearest_sampler;
// lavapipe has no shaderStorageImageReadWithoutFormat: storage images name their format.
layout(set = 0, binding = 2, rgba16f) uniform writeonly image2D dst;
layout(set = 0, binding = 3, std140) uniform Params {
  vec4 gain;
};

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const ivec2 size = imageSize(dst);
  if (any(greaterThanEqual(p, size))) return;
  const vec2 uv = (vec2(p) + 0.5) / vec2(size);
  imageStore(dst, p, textureLod(sampler2D(src, nearest_sampler), uv, 0.0) * gain);
}
