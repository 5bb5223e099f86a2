// SssGaussiansPass ("sss gaussians"): each Gaussian of the material's fit as its own
// separable blur, incrementally (GaussianPingPong): pass g blurs the previous result by
// v_g - v_{g-1} (horizontal -> blur_temp, vertical -> blur_a / blur_b alternately) and accumulates
// w_g x (E * G(v_g)) into accum, which is R * E for a flat surface (the weights already
// sum to the total reflectance).
#pragma once

#include "renderer/Program.h"
#include "renderer/FrameResources.h"
#include "renderer/GaussianPingPong.h"
#include "renderer/graph/FrameGraph.h"

namespace sss::renderer {

class SssGaussiansPass {
 public:
  static constexpr const char* kName = "sss gaussians";

  // gaussians: the most Gaussians of any material (passes to run).
  SssGaussiansPass(const FrameResources& resources, int gaussians);
  void add_to(graph::FrameGraph& graph) const;
  // Points the sets at the current targets (after FrameTargets were recreated; none of
  // them may be in use by the GPU).
  void write_descriptors();
  // After the materials changed: the new most Gaussians of any material (> 0).
  void set_gaussians(int gaussians) { gaussians_ = gaussians; }

 private:
  const FrameResources& r_;
  int gaussians_;
  Program program_;
  GaussianPingPong blur_;  // irradiance, then blur_a / blur_b via blur_temp
};

}  // namespace sss::renderer
