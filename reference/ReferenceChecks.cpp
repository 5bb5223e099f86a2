#include "reference/ReferenceChecks.h"

#include "image/Image.h"
#include "reference/ProbeReference.h"
#include "reference/SamplePasses.h"
#include "reference/TileMerge.h"
#include "scene/Mesh.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sss::reference::detail {

void check_options(const ReferenceOptions& o) {
  if (o.width == 0 || o.height == 0)
    throw std::invalid_argument("width/height: the image must be at least 1x1, got " +
                                std::to_string(o.width) + "x" + std::to_string(o.height));
  if (o.width > 16384 || o.height > 16384)
    throw std::invalid_argument("width/height: at most 16384 pixels a side");
  if (!(std::isfinite(o.spacing_mfp) && o.spacing_mfp > 0.0))
    throw std::invalid_argument("spacing: must be finite and > 0, got " + message_number(o.spacing_mfp));
  if (!(std::isfinite(o.max_solid_angle) && o.max_solid_angle >= 0.0))
    throw std::invalid_argument("error bound: the maximum solid angle must be finite and >= 0, got " +
                                message_number(o.max_solid_angle));
  if (!(std::isfinite(o.exposure) && o.exposure >= 0.0f))
    throw std::invalid_argument("exposure: must be finite and >= 0, got " + message_number(o.exposure));
  if (std::uint64_t(o.width) * o.height > image::kMaxImagePixels)
    throw std::invalid_argument("width/height: at most " + std::to_string(image::kMaxImagePixels) +
                                " pixels (what image files are read back with)");
  if (o.thickness == Thickness::ShadowMap && o.transmission != Transmission::Local)
    throw std::invalid_argument("thickness: shadow-map applies to transmission local only, not " +
                                std::string(transmission_name(o.transmission)));
  if ((o.shadows == Shadows::ShadowMap || o.thickness == Thickness::ShadowMap) &&
      (o.shadow_map_size < 1 || o.shadow_map_size > 16384))
    throw std::invalid_argument("shadow map size: must be 1..16384, got " + std::to_string(o.shadow_map_size));
  if (o.threads < 0) throw std::invalid_argument("threads: must be >= 0 (0: all), got " + std::to_string(o.threads));
  if (o.estimator == Estimator::Probe) {
    check_sample_counts(o.spp, o.target_error, "probe batches");
    check_tile(o.tile, o.height, o.target_error);
    if (o.transmission != Transmission::Profile)
      throw std::invalid_argument("transmission: " + std::string(transmission_name(o.transmission)) +
                                  " applies to the octree estimator only");
  } else if (!o.tile.whole()) {
    throw std::invalid_argument("tile: applies to the probe estimator only (the octree renders whole frames)");
  } else if (o.spp != 0 || o.target_error != 0.0) {
    throw std::invalid_argument("spp/target error: apply to the probe estimator only (the octree's error is set by "
                                "the spacing and the error bound)");
  }
}

void check_scene(const scene::Scene& s) {
  if (s.cameras.empty()) throw std::invalid_argument("scene '" + s.name + "' has no camera");
  for (const scene::Instance& inst : s.instances)
    if (inst.mesh >= s.meshes.size())
      throw std::invalid_argument("instance '" + inst.node + "': mesh index out of range");
  for (const scene::Mesh& mesh : s.meshes) {
    if (auto broken = scene::check_mesh(mesh)) throw std::invalid_argument("mesh '" + mesh.name + "': " + *broken);
    if (mesh.material >= s.materials.size())
      throw std::invalid_argument("mesh '" + mesh.name + "': material index out of range");
  }
}

double smallest_mfp(const profiles::Medium& m) {
  double mfp = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c) mfp = std::min(mfp, m.channel(c).mfp_reduced());
  return mfp;
}

}  // namespace sss::reference::detail
