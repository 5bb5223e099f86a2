// FrameGraph: the frame as a list of passes that declare how they use each image, and
// the barriers and layout transitions derived from those declarations (DESIGN.md §8,
// after Filament's frame graph; single queue, one command buffer).
//
// A pass is a name and one or more steps. A step declares the images it reads and
// writes (an `Access`: stages, access mask, layout, and whether it writes), then records
// its commands. Before each step the graph records one vkCmdPipelineBarrier2 with what
// the step needs after everything earlier in the frame:
//   - read after write: the writer's stages and writes made visible to the reader's
//     stages and reads, once per kind of reader (a second compute read of the same
//     result needs no second barrier);
//   - write after read or write, and any change of layout: the earlier readers' and
//     writer's stages before the new access;
//   - once a barrier has made a write available, later ones chain after its readers with
//     no source access (the writer's access need not match the layout any more).
// Each image's first use in the frame is one transition from UNDEFINED (last frame's
// contents are not needed) in a single barrier at the start, after everything the
// previous frame did. An image read before anything writes it (bound, but not fetched in
// this mode) goes to GENERAL there and to its read-only layout at the use. After the last pass, images given to keep() are left in their
// layout for readback and presentation.
//
// Passes run in the order they are added: the renderer adds them in an order where every
// read follows its writer. The graph does not reorder them, and images that the frame
// uses but does not own (the texture path's atlases, the environment maps, uploaded
// once) are not declared: they keep their own barriers.
//
// The pass's name labels its GPU timer scope and debug marker (vk::GpuTimer), so
// `--stats` and RenderDoc show the same names. describe() lists the passes with their
// steps' reads and writes: docs/ARCHITECTURE.md's frame table is its output.
#pragma once

#include "renderer/vk/Barrier.h"

#include <vulkan/vulkan.h>

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace sss::vk {
class GpuTimer;
class Image;
}  // namespace sss::vk

namespace sss::renderer::graph {

struct Access {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  bool writes = false;
  const char* what = "";  // for describe()
};

// The uses the frame's passes make of images.
namespace use {
inline constexpr VkPipelineStageFlags2 kFragmentTests =
    VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
inline constexpr Access kColorAttachment{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true,
                                         "colour attachment"};
// A colour attachment that compute passes also read and write (no transition between).
inline constexpr Access kColorAttachmentGeneral{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                                VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                                                VK_IMAGE_LAYOUT_GENERAL, true,
                                                "colour attachment"};
inline constexpr Access kDepthAttachment{
    kFragmentTests,
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
    VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true, "depth attachment"};
// Depth tested, not written, by a draw (the texture path's lookup).
inline constexpr Access kDepthTest{kFragmentTests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
                                   VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, false, "depth test"};
// A depth image sampled by compute in the layout the depth test also reads.
inline constexpr Access kSampledDepth{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                      VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, false, "sampled"};
// An attachment's result sampled by compute.
inline constexpr Access kSampled{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, "sampled"};
// A compute target read by compute (sampler or storage load).
inline constexpr Access kComputeRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT |
                                         VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
                                     VK_IMAGE_LAYOUT_GENERAL, false, "read"};
// A compute target written (and possibly read) as a storage image.
inline constexpr Access kComputeWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                      VK_IMAGE_LAYOUT_GENERAL, true, "storage write"};
inline constexpr Access kClear{VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                               VK_IMAGE_LAYOUT_GENERAL, true, "clear"};
inline constexpr Access kCopySource{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false, "copy source"};
inline constexpr Access kCopyDestination{VK_PIPELINE_STAGE_2_COPY_BIT,
                                         VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                         VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true,
                                         "copy destination"};
}  // namespace use

struct ImageUse {
  const vk::Image* image;
  Access access;
};

// One derived dependency: `image` from `old_layout` to `new_layout` (equal: no
// transition), after `src`, before `dst`.
struct Transition {
  const vk::Image* image;
  VkImageLayout old_layout, new_layout;
  vk::Scope src, dst;
};

// The state of each image through the frame and the dependencies each new use needs
// (the rules above). No Vulkan calls: tests/unit drive it with made-up images.
class BarrierTracker {
 public:
  // The first use of every image in `steps`' order, as transitions from UNDEFINED after
  // `before` (the previous frame). Afterwards each image is in its first use's layout
  // and that use needs nothing more.
  std::vector<Transition> begin(const std::vector<const std::vector<ImageUse>*>& steps,
                                vk::Scope before);
  // What `uses` need after everything tracked so far; records them as done.
  std::vector<Transition> use(const std::vector<ImageUse>& uses);
  // `image` into `layout` after everything tracked (nothing if it is already there).
  std::vector<Transition> leave(const vk::Image& image, VkImageLayout layout, vk::Scope then);

 private:
  struct State {
    const vk::Image* image;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    vk::Scope write;    // the last write (none after the first-use transition)
    vk::Scope reads;    // stages and accesses that read since the last write
    vk::Scope visible;  // what the last write has been made visible to
  };
  State& state(const vk::Image* image);
  // The source scope of a dependency on everything tracked for the image.
  static vk::Scope after(const State& s);
  std::vector<State> states_;
};

class FrameGraph {
 public:
  using Commands = std::function<void(VkCommandBuffer)>;

  class PassBuilder {
   public:
    // A step: its image uses, then its commands (recorded after the barriers they need).
    PassBuilder& step(std::vector<ImageUse> uses, Commands commands);

   private:
    friend class FrameGraph;
    PassBuilder(FrameGraph& graph, std::size_t pass) : graph_(graph), pass_(pass) {}
    FrameGraph& graph_;
    std::size_t pass_;
  };

  // timed: a GPU timer scope and debug label of the pass's name (`--stats`); the frame's
  // clear is not timed.
  PassBuilder add_pass(std::string_view name, bool timed = true);
  // After the last pass, `image` is in `layout` (readback, presentation).
  void keep(const vk::Image& image, VkImageLayout layout);

  // Records every pass: the first-use transitions, each step's barriers and commands
  // inside its pass's timer scope, then the transitions keep() asked for.
  void record(VkCommandBuffer cmd, vk::GpuTimer& timer) const;

  // One line per step: the pass, then each image it reads or writes and how.
  std::string describe() const;
  // The passes' names in order, joined by " -> " (renderer/README.md's pass lists).
  std::string pass_order() const;

  struct Step {
    std::vector<ImageUse> uses;
    Commands commands;
  };
  struct Pass {
    std::string name;
    bool timed = true;
    std::vector<Step> steps;
  };
  const std::vector<Pass>& passes() const { return passes_; }

 private:
  std::vector<Pass> passes_;
  std::vector<std::pair<const vk::Image*, VkImageLayout>> kept_;
};

}  // namespace sss::renderer::graph
