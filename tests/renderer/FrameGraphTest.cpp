// The frame graph's barriers, derived from declared image uses (renderer/graph): each
// rule of FrameGraph.h on made-up steps, then the real frame's description against the
// table in docs/ARCHITECTURE.md. The frame's barriers themselves are checked by the
// synchronization validation that every RenderTest runs with.
#include "RenderTest.h"

#include "renderer/Renderer.h"
#include "renderer/graph/FrameGraph.h"
#include "scene/BuiltinScenes.h"

#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <sstream>

namespace sss::renderer::testing {
namespace {

using graph::BarrierTracker;
using graph::ImageUse;
using graph::Transition;
namespace use = graph::use;

class FrameGraphTest : public RenderTest {
 protected:
  vk::Image image(const char* name) {
    return vk::Image(ctx(), vk::ImageDesc{4, 4, VK_FORMAT_R16G16B16A16_SFLOAT,
                                          VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                              VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                          name});
  }
};

constexpr vk::Scope kBefore{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT};

TEST_F(FrameGraphTest, FirstUsesAreOneTransitionFromUndefinedEach) {
  const vk::Image a = image("a"), b = image("b");
  const std::vector<ImageUse> s1{{&a, use::kColorAttachment}};
  const std::vector<ImageUse> s2{{&a, use::kSampled}, {&b, use::kComputeWrite}};
  BarrierTracker tracker;
  const std::vector<Transition> first = tracker.begin({&s1, &s2}, kBefore);
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].image, &a);
  EXPECT_EQ(first[0].old_layout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(first[0].new_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(first[0].src.stages, kBefore.stages);
  EXPECT_EQ(first[0].dst.stages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  EXPECT_EQ(first[1].image, &b);
  EXPECT_EQ(first[1].new_layout, VK_IMAGE_LAYOUT_GENERAL);
  // The first uses need nothing more.
  EXPECT_TRUE(tracker.use(s1).empty());
  // a: written as an attachment, now sampled: one transition with the write made visible.
  const std::vector<Transition> t = tracker.use(s2);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].image, &a);
  EXPECT_EQ(t[0].old_layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(t[0].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(t[0].src.access, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  EXPECT_EQ(t[0].dst.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

TEST_F(FrameGraphTest, AReadAfterAWriteWaitsOncePerKindOfReader) {
  const vk::Image a = image("a");
  const std::vector<ImageUse> write{{&a, use::kComputeWrite}};
  const std::vector<ImageUse> read{{&a, use::kComputeRead}};
  BarrierTracker tracker;
  tracker.begin({&write, &read}, kBefore);
  EXPECT_TRUE(tracker.use(write).empty());
  const std::vector<Transition> t = tracker.use(read);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].old_layout, t[0].new_layout);  // GENERAL throughout: a dependency only
  EXPECT_EQ(t[0].src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(t[0].dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  // A second compute read of the same result: already visible.
  EXPECT_TRUE(tracker.use(read).empty());
}

TEST_F(FrameGraphTest, AWriteWaitsForTheReadsAndTheWriteBeforeIt) {
  const vk::Image a = image("a");
  const std::vector<ImageUse> write{{&a, use::kComputeWrite}};
  const std::vector<ImageUse> read{{&a, use::kComputeRead}};
  BarrierTracker tracker;
  tracker.begin({&write}, kBefore);
  tracker.use(write);
  tracker.use(read);
  // Write after read (and after the first write): the readers' stages; the read's barrier
  // already made the first write available, so no source access.
  const std::vector<Transition> t = tracker.use(write);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(t[0].src.access, VK_ACCESS_2_NONE);
  EXPECT_EQ(t[0].dst.access, use::kComputeWrite.access);
  // Two writes in a row also wait (write after write), and the first one's writes are
  // made available.
  const std::vector<Transition> again = tracker.use(write);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST_F(FrameGraphTest, ReadsInTwoLayoutsTransitionBetweenThem) {
  const vk::Image a = image("a");
  const std::vector<ImageUse> copy{{&a, use::kCopySource}};
  const std::vector<ImageUse> write{{&a, use::kComputeWrite}};
  BarrierTracker tracker;
  tracker.begin({&write}, kBefore);
  tracker.use(write);
  const std::vector<Transition> to_copy = tracker.use(copy);
  ASSERT_EQ(to_copy.size(), 1u);
  EXPECT_EQ(to_copy[0].new_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  // Back to GENERAL for a write: after the copy's read.
  const std::vector<Transition> back = tracker.use(write);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].old_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_EQ(back[0].new_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(back[0].src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT);
  // The copy's barrier made the write available: no storage write named against the
  // TRANSFER_SRC layout (best practices, ImageBarrierAccessLayout).
  EXPECT_EQ(back[0].src.access, VK_ACCESS_2_NONE);
  // leave(): nothing when the image is already in the layout asked for.
  EXPECT_TRUE(tracker.leave(a, VK_IMAGE_LAYOUT_GENERAL, vk::kAllCommands).empty());
  EXPECT_EQ(tracker.leave(a, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, vk::kAllCommands).size(), 1u);
}

// An image only read this frame (its shader skips it in this mode) goes to GENERAL at the
// start and to its read-only layout at the use, chained through the reader's stages: from
// UNDEFINED straight to a read-only layout would read discarded contents.
TEST_F(FrameGraphTest, AnImageReadBeforeAnyWriteReachesItsLayoutThroughGeneral) {
  const vk::Image a = image("a");
  const std::vector<ImageUse> read{{&a, use::kSampled}};
  BarrierTracker tracker;
  const std::vector<Transition> first = tracker.begin({&read}, kBefore);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].new_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(first[0].dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  const std::vector<Transition> t = tracker.use(read);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].old_layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(t[0].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(t[0].src.stages, first[0].dst.stages);  // chained after the first transition
  EXPECT_TRUE(tracker.use(read).empty());
}

// A second kind of reader after a change of layout: the write is already available, so
// the barrier chains after the first reader and names no source access (the writer's
// attachment write would not match the read-only layout).
TEST_F(FrameGraphTest, ASecondKindOfReaderChainsAfterTheFirstWithoutTheWritersAccess) {
  const vk::Image depth(ctx(), vk::ImageDesc{4, 4, VK_FORMAT_D32_SFLOAT,
                                             VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT |
                                                 VK_IMAGE_USAGE_SAMPLED_BIT,
                                             "depth"});
  const std::vector<ImageUse> write{{&depth, use::kDepthAttachment}};
  const std::vector<ImageUse> test{{&depth, use::kDepthTest}};
  const std::vector<ImageUse> sample{{&depth, use::kSampledDepth}};
  BarrierTracker tracker;
  tracker.begin({&write}, kBefore);
  tracker.use(write);
  const std::vector<Transition> to_test = tracker.use(test);
  ASSERT_EQ(to_test.size(), 1u);
  EXPECT_EQ(to_test[0].src.access, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
  const std::vector<Transition> to_sample = tracker.use(sample);
  ASSERT_EQ(to_sample.size(), 1u);
  EXPECT_EQ(to_sample[0].old_layout, to_sample[0].new_layout);
  EXPECT_EQ(to_sample[0].src.access, VK_ACCESS_2_NONE);
  EXPECT_EQ(to_sample[0].src.stages, use::kFragmentTests);  // the writer's and the test's
  EXPECT_EQ(to_sample[0].dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
}

TEST_F(FrameGraphTest, AStepThatUsesAnImageInTwoLayoutsIsRefused) {
  const vk::Image a = image("a");
  const std::vector<ImageUse> both{{&a, use::kSampled}, {&a, use::kComputeWrite}};
  BarrierTracker tracker;
  EXPECT_THROW(tracker.begin({&both}, kBefore), std::logic_error);
}

// The code block of the source file `path` (from the source root) between the markers
// "<!-- NAME: begin -->" and "<!-- NAME: end -->": the docs' parts that the graph generates.
// Empty when the file or a marker is missing.
std::optional<std::string> generated_block(const std::string& path, const std::string& name) {
  std::ifstream in(std::string(SSS_SOURCE_DIR) + "/" + path);
  if (!in) return std::nullopt;
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string text = doc.str();
  const std::string begin = "<!-- " + name + ": begin -->\n```\n", end = "```\n<!-- " + name + ": end -->";
  const std::size_t b = text.find(begin), e = text.find(end);
  if (b == std::string::npos || e == std::string::npos || e < b + begin.size()) return std::nullopt;
  return text.substr(b + begin.size(), e - b - begin.size());
}

// The frame table in docs/ARCHITECTURE.md is the default frame's describe(), between
// the markers (regenerate: `sss-viewer builtin:bunny --describe-frame`).
TEST_F(FrameGraphTest, TheArchitectureDocsFrameTableIsTheGraphsDescription) {
  RenderOptions options;  // the defaults: separable, transmission, no debug view
  options.width = 64;
  options.height = 36;
  Renderer renderer(ctx(), scene::sphere_scene(), options);
  const std::string described = renderer.describe_frame();
  const std::optional<std::string> table = generated_block("docs/ARCHITECTURE.md", "frame graph");
  ASSERT_TRUE(table) << "docs/ARCHITECTURE.md: no '<!-- frame graph: begin/end -->' code block";
  EXPECT_EQ(*table, described);
  // Every pass the frame times is in it, in order.
  EXPECT_NE(described.find("shadow | "), std::string::npos);
  EXPECT_LT(described.find("lighting | "), described.find("composite | "));
}

// renderer/README.md's pass lists, between the markers, are each technique's pass_order()
// (and the two optional passes'), so that the list cannot drift from the graph. On a
// mismatch the expected block is printed: paste it between the markers.
TEST_F(FrameGraphTest, TheRendererReadmesPassListsAreTheGraphsPassOrder) {
  struct Case {
    std::string label;
    RenderOptions options;
  };
  std::vector<Case> cases;
  for (const SssTechnique t :
       {SssTechnique::Off, SssTechnique::Separable, SssTechnique::Gaussians, SssTechnique::Texture}) {
    RenderOptions o;
    o.technique = t;
    cases.push_back({std::string(technique_name(t)), o});
  }
  RenderOptions fxaa;
  fxaa.antialias = Antialias::Fxaa;
  cases.push_back({"separable, --aa fxaa", fxaa});
  RenderOptions debug;
  debug.debug_view = DebugView::Irradiance;
  cases.push_back({"separable, --debug-view irradiance", debug});
  std::string expected;
  for (Case& c : cases) {
    c.options.width = 64;
    c.options.height = 36;
    Renderer renderer(ctx(), scene::sphere_scene(), c.options);
    std::string label = c.label + ":";
    label.resize(std::max<std::size_t>(label.size() + 1, 36), ' ');
    expected += label + renderer.frame_pass_order() + "\n";
  }
  const std::optional<std::string> lists = generated_block("renderer/README.md", "pass order");
  ASSERT_TRUE(lists) << "renderer/README.md: no '<!-- pass order: begin/end -->' code block";
  EXPECT_EQ(*lists, expected)
      << "renderer/README.md's pass lists are stale; the graph's, to paste between the markers:\n"
      << expected;
  // Each technique's blur is in its own list, between lighting and composite.
  EXPECT_NE(expected.find("lighting -> sss separable"), std::string::npos);
  EXPECT_NE(expected.find("sss gaussians"), std::string::npos);
}

}  // namespace
}  // namespace sss::renderer::testing
