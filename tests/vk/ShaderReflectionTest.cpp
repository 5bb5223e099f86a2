// The descriptor bindings reflected from the shaders at build time
// (cmake/ShaderReflect.cmake) against what the GLSL declares: numbers, descriptor types
// (a sampler, a storage image, a uniform and a storage block), array sizes and stages. The
// frame's passes build their set layouts from these alone, so a parser that misread one
// would fail here by name rather than as a validation message in some later frame.
#include "renderer/vk/Descriptors.h"
#include "shaders/gbuffer.frag.bindings.h"
#include "shaders/gbuffer.vert.bindings.h"
#include "shaders/lighting.comp.bindings.h"
#include "shaders/selftest_triangle.vert.bindings.h"
#include "shaders/shared/frame.h"
#include "shaders/texture_gather.frag.bindings.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sss::vk {
namespace {

namespace lighting = shader::bindings::lighting_comp;

// lighting.comp: `layout(set = 0, binding = N)` for each of these.
static_assert(lighting::Frame == 0 && lighting::Lights == 1 && lighting::Materials == 2);
static_assert(lighting::depth_tex == 3 && lighting::irradiance_img == 7 && lighting::dfg_tex == 12);

TEST(ShaderReflection, TypesComeFromTheDeclarations) {
  EXPECT_EQ(lighting::Frame.type, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);      // uniform Frame {}
  EXPECT_EQ(lighting::Materials.type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);  // readonly buffer
  EXPECT_EQ(lighting::shadow_tex.type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);  // 2DArrayShadow
  EXPECT_EQ(lighting::normal_tex.type, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);  // sampler2D
  EXPECT_EQ(lighting::irradiance_img.type, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);       // image2D
  EXPECT_EQ(lighting::irradiance_img.stages, VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT));
  // Every binding the shader uses, once: 0 .. 13.
  EXPECT_EQ(lighting::kAll.size(), 14u);
}

TEST(ShaderReflection, ArraysAndStagesOfGraphicsShaders) {
  namespace gather = shader::bindings::texture_gather_frag;
  EXPECT_EQ(gather::scattered.count, shader::kMaxTextureObjects);
  EXPECT_EQ(gather::scattered.stages, VkShaderStageFlags(VK_SHADER_STAGE_FRAGMENT_BIT));
  EXPECT_EQ(shader::bindings::gbuffer_frag::textures.count, shader::kMaxTextures);
  EXPECT_EQ(shader::bindings::gbuffer_vert::Frame.stages,
            VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT));
  EXPECT_TRUE(shader::bindings::selftest_triangle_vert::kAll.empty());  // no descriptors
}

TEST(ShaderReflection, ALayoutOfTwoStagesJoinsTheirBindings) {
  DescriptorSetLayoutBuilder b;
  b.add(shader::bindings::gbuffer_vert::kAll).add(shader::bindings::gbuffer_frag::kAll);
  ASSERT_EQ(b.bindings().size(), 2u);
  EXPECT_EQ(b.bindings()[0].binding, 0u);  // Frame: read by both stages
  EXPECT_EQ(b.bindings()[0].stageFlags,
            VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT));
  EXPECT_EQ(b.bindings()[1].descriptorCount, shader::kMaxTextures);
  // Two shaders that disagree on a binding's type cannot share a set.
  const ShaderBinding other[] = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT}};
  EXPECT_THROW(b.add(other), std::logic_error);
}

}  // namespace
}  // namespace sss::vk
