// LinePrefix ("sss prefix", sss_prefix.comp): running sums of an SSS pass's input along
// the rows or the columns of the geometry's rect, restarting at every edge of a run of
// one material's surface, into FrameTargets::sss_prefix. From two of them a 1D blur reads
// the input's mean over any interval of a run at the cost of two fetches, which the
// separable kernel's wide cells need so that a light edge does not come out as a
// staircase (issue 20, "separable streaks"). The gaussians mode does not need it: its
// strided taps see an input the narrower Gaussians already blurred (EdgeTest).
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/graph/FrameGraph.h"

#include <span>
#include <vector>

namespace sss::renderer {

class LinePrefix {
 public:
  static constexpr const char* kName = "sss prefix";

  // max_inputs: the most images record() will be given.
  LinePrefix(const FrameResources& resources, int max_inputs);
  // One descriptor set per input image (after FrameTargets were recreated: the new ones).
  void write_descriptors(std::span<const vk::Image* const> inputs);
  // The step that sums `input` (one of write_descriptors' images) along rows (vertical
  // false) or columns.
  void add_step(graph::FrameGraph::PassBuilder& pass, const vk::Image& input, bool vertical) const;

 private:
  const FrameResources& r_;
  Program program_;
  std::vector<VkDescriptorSet> sets_;
  std::vector<const vk::Image*> inputs_;
};

}  // namespace sss::renderer
