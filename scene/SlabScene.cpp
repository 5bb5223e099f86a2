// builtin:slab, a thin slab lit from behind: the transmission check (issue 6).
//
// Geometry: a 30 x 30 mm slab, 2 mm thick, centred on the origin in the xy plane: the
// front face is z = +1 mm (normal +z), the back face z = -1 mm.
// Material: skin2's coefficients as a finite slab (CoefficientSource with thickness_mm =
// 2), model Multipole (the model that has a transmittance), roughness 1, specular 0 (all
// incident light enters), base colour 1, post-scatter. `sss-fit profile --preset skin2
// --model multipole --thickness 2` gives the total transmittance T = (0.436, 0.234,
// 0.131) and reflectance R = (0.473, 0.412, 0.339): the front glows orange while the
// light reaching the back is white.
// Why skin2 at 2 mm: the slab is 2.2 (R) to 3.9 (B) reduced mean free paths thick, where
// the multipole is trustworthy (its R is within 3% of Monte Carlo's here; skin1 at 2 mm
// is only 1.5 free paths thick in red and 8% off), and every channel still transmits
// more than 10%. Cost: the SSS area, 1,920 mm², is 0.07 of mfp² × 1e5 for the smallest
// reduced mean free path (blue, 0.52 mm), so the golden frame stays cheap.
// Light: one directional light travelling +z (normal incidence on the back face, from
// behind the slab towards the camera), E = 3. The front face and the four sides face away
// from it or lie along it (n·l <= 0): nothing the camera sees is lit directly. 99% of
// the transmitted red light leaves within 8.6 mm of where it entered (sss-fit's T(r)), so
// at the centre, 15 mm from every side, the front's exitant flux is T·E = (1.31, 0.70,
// 0.39).
// No fill light, on purpose: with one, the front would show reflectance R·E_fill plus
// transmission, and a transmission error would hide in the sum; reflectance is checked by
// builtin:edge, builtin:sphere and builtin:materials. The cost: a renderer without
// transmission shows a black slab.
// Camera: perspective, in front (+z side), slightly above and to the right, looking at the
// slab's centre, so the front face fills most of the frame and the +x and +y sides show
// as thin strips.
#include "scene/BuiltinScenes.h"

#include "scene/Shapes.h"

#include "profiles/Presets.h"

#include <stdexcept>

namespace sss::scene {

namespace {

constexpr double kSlabSizeMm = 30.0;
constexpr double kSlabThicknessMm = 2.0;
constexpr const char* kPreset = "skin2";

}  // namespace

Scene slab_scene() {
  Scene s;
  s.name = "builtin:slab";
  s.mm_per_unit = 1000.0;
  const float mm = float(1.0 / s.mm_per_unit);  // one mm in scene units

  const profiles::Preset* preset = profiles::find_preset(kPreset);
  if (!preset) throw std::invalid_argument(std::string("no preset ") + kPreset);
  profiles::Medium medium = profiles::preset_medium(*preset);
  medium.thickness_mm = kSlabThicknessMm;
  auto made = make_sss_material(CoefficientSource{medium}, profiles::Model::Multipole);
  if (auto* e = std::get_if<FieldError>(&made)) throw std::invalid_argument(e->what());

  Material slab;
  slab.name = std::string(kPreset) + " slab";
  slab.base_color = glm::vec4(1.0f);
  slab.metallic = 0.0f;
  slab.roughness = 1.0f;
  slab.specular = 0.0f;
  slab.sss = std::get<SssMaterial>(std::move(made));
  s.materials.push_back(slab);

  const float half = float(0.5 * kSlabSizeMm) * mm, half_t = float(0.5 * kSlabThicknessMm) * mm;
  Mesh box = make_box({-half, -half, -half_t}, {half, half, half_t}, 0);
  box.name = "slab";
  s.meshes.push_back(std::move(box));
  s.instances.push_back({0, glm::mat4(1.0f), "slab"});

  s.lights.push_back(directional_light("back light (behind the slab)", {0.0f, 0.0f, 1.0f}, 3.0f));

  // Seen from (0.25, 0.2, 1) of the way out: about 17 degrees off the normal. 0.85 of the
  // bounding sphere leaves a margin around the square face in a 16:9 frame.
  Camera cam = frame_bounds(s.bounds(), {-0.25f, -0.2f, -1.0f}, 0.6f, 0.85f);
  cam.name = "front, slightly oblique";
  s.cameras.push_back(cam);
  return s;
}

}  // namespace sss::scene
