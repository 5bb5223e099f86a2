// SssSeparablePass ("sss separable"): Jimenez et al. 2015. Each SSS material's 1D kernel
// (profiles::make_separable_kernel: offsets in mm, RGB weights summing to 1) is applied
// horizontally to the irradiance (-> sss_line), then vertically, with the kernel's mm
// turned into pixels from the depth and the projection and follow-surface fallback. Each
// 1D pass first takes running sums of its input along its lines (LinePrefix), so a tap reads the input's mean over its whole cell rather than one point
// (sss_separable.comp). The vertical half
// also composites the pixels it scattered (x total reflectance x albedo / pi + specular
// -> hdr, display; composite.glsl), so that the scattered result never goes through an
// image; CompositePass does every other pixel.
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/LinePrefix.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class SssSeparablePass {
 public:
  static constexpr const char* kName = "sss separable";

  explicit SssSeparablePass(const FrameResources& resources);
  void add_to(graph::FrameGraph& graph) const;
  // Points the sets at the current targets (after FrameTargets were recreated; none of
  // them may be in use by the GPU).
  void write_descriptors();
  // The scattered debug view: the vertical pass also writes R * E into blur_a.
  void set_write_scattered(bool on) { write_scattered_ = on; }

 private:
  const FrameResources& r_;
  Program program_;
  LinePrefix prefix_;  // the running sums each 1D pass reads
  VkDescriptorSet horizontal_ = VK_NULL_HANDLE;
  VkDescriptorSet vertical_ = VK_NULL_HANDLE;
  bool write_scattered_ = false;
};

}  // namespace sss::renderer
