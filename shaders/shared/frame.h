// Layouts shared by the renderer's passes (renderer/*Pass.cpp) and their shaders: the
// frame uniforms, the material/profile table, the lights, and the push constants. Valid
// C++ and GLSL; every struct is made of vec4/mat4/scalar members in std140/std430 order
// so that the C++ layout equals the GLSL one (static_asserts at the end).
//
// C++:  #include "shaders/shared/frame.h"      GLSL:  #include "shared/frame.h"
#ifndef SSS_SHADERS_SHARED_FRAME_H
#define SSS_SHADERS_SHARED_FRAME_H

#include "config.h"

// Lights the frame shades (the rest are ignored with a warning); each may have a shadow
// map layer.
#define SSS_MAX_LIGHTS 4
// The most taps of a separable kernel (odd).
#define SSS_MAX_TAPS 33
// Gaussian blur half-taps at most per 1D pass (gaussians mode); wider Gaussians are
// sampled with an integer stride.
#define SSS_GAUSSIAN_HALF_TAPS 12
// Light types (Light::type).
#define SSS_LIGHT_DIRECTIONAL 0
#define SSS_LIGHT_POINT 1
#define SSS_LIGHT_SPOT 2
// Material textures (base colour, normal maps) bound in one frame; more are ignored.
// lavapipe allows 32 samplers per stage; 30 leaves room for two more beside them.
#define SSS_MAX_TEXTURES 30
// Objects the texture path gives an irradiance atlas in one frame (more are drawn without
// spread, with a warning); texels a seam dilation fills around each UV island.
#define SSS_MAX_TEXTURE_OBJECTS 16
#define SSS_TEXTURE_DILATE_TEXELS 4
// G-buffer material id: albedo.a = (material index + 1) / 255; 0 is background.
#define SSS_MAX_MATERIALS 254

#ifdef __cplusplus
#include <cstddef>  // offsetof, in the layout checks at the end
namespace sss::shader {
struct vec3 {  // std430: 16-byte aligned, a scalar may follow in its last 4 bytes
  float x = 0, y = 0, z = 0;
};
struct vec4 {
  float x = 0, y = 0, z = 0, w = 0;
};
struct mat4 {
  vec4 c[4];  // columns, as GLSL and glm store them
};
#endif

// Uniform buffer of the frame (set 0 of every pass that needs it).
struct FrameUniforms {
  mat4 view_proj;      // world -> clip
  mat4 inv_view_proj;  // clip -> world
  mat4 inv_proj;       // clip -> view
  vec4 camera;         // xyz camera position (world), w 1 = orthographic
  vec4 forward;        // xyz camera view direction (world, unit)
  vec4 viewport;       // width, height, 1/width, 1/height
  vec4 scale;          // x mm per scene unit, y P[0][0], z |P[1][1]|, w exposure
  vec4 options;        // x light count, y SSS technique (SSS_TECHNIQUE_*),
                       // z surface key stride in mm (sss.glsl), w 1 = transmission
                       // through thin parts (lighting.comp; RenderOptions::transmission)
  vec4 rect;           // x0, y0, x1, y1 (pixels, x1 y1 exclusive): the screen passes
                       // (lighting, SSS, composite) cover this rect; outside it every pixel
                       // is background (CameraSetup.h: geometry_rect)
  vec4 flags;          // x 1 = directional Fresnel factors on subsurface light
                       // (RenderOptions::fresnel; shading.glsl, composite.glsl); y 1 =
                       // single scattering S(1) per pixel (RenderOptions::
                       // single_scattering; shading.glsl); z 1 = an environment light
                       // (LightBlock::environment), 2 = one whose blocked part the
                       // G-buffer's and the atlases' sky targets hold (shading.glsl,
                       // RenderOptions::sky_occlusion); w 1 = the environment behind
                       // the geometry in the display image (composite.comp; needs z)
};

struct GpuLight {
  mat4 shadow_matrix;  // world -> shadow clip (layer = index); identity when unshadowed
  mat4 shadow_inverse; // shadow clip -> world (thickness.glsl), computed on the CPU once
  vec4 color;          // rgb colour x intensity (E for directional, I otherwise), w type
  vec4 direction;      // xyz travel direction (unit), w cos(outer cone)
  vec4 position;       // xyz position, w cos(inner cone)
  vec4 mask;           // half-space: lit where dot(xyz, p) + w < 0
  vec4 shadow;         // x has mask, y has shadow map, z normal offset (units), w depth bias
};

struct LightBlock {
  GpuLight lights[SSS_MAX_LIGHTS];
  // The environment's irradiance as 9 spherical-harmonic coefficients (rgb; w 0), in the
  // order of scene::sh_basis: E(N) = sum_k environment[k] Y_k(N) (scene/Environment.h).
  vec4 environment[9];
};

// One material: surface parameters and, when it scatters, its profile as a fit and as a
// separable kernel (both in object mm; the material's scale is already in them).
// One material as the shaders read it; renderer::encode() (MaterialTable.cpp) is the only
// code that writes one. Each vec3 starts a 16-byte row and the scalar after it fills the
// row (std430), so the rows below are the layout. A material without SSS keeps the
// defaults below its surface row (total_reflectance 1: Lambert).
struct GpuMaterial {
  float f0;                 // 0.04 x specular (a dielectric's normal-incidence Fresnel)
  float metallic;
  float roughness;          // GGX alpha = roughness^2 (shading.glsl)
  int gaussian_count;       // Gaussians in the fit (0 without SSS), <= SSS_MAX_GAUSSIANS
  vec3 total_reflectance;   // T per channel (the separable kernel's, the profile's total)
  int scatters;             // 1 when SSS is enabled
  vec3 slab_transmittance;  // a slab's total transmittance (the multipole's T(r) fitted with
                            // the reflectance fit's variances, MaterialTable.cpp)
  float slab_thickness_mm;  // 0: not a slab (lighting.comp uses the profile through the
                            // shadow-map thickness)
  vec3 eta;                 // the medium's index of refraction η per channel
  int separable_taps;       // taps of the separable kernel
  vec3 exit_norm;           // 1/c, c = 1 - 2 m1(1/η) (profiles::fresnel_exit_normalization)
  float range_mm;           // the separable kernel's follow-surface width
  vec3 single_albedo;       // σs/σt of the real (not reduced) coefficients (S(1))
  int pre_post;             // 1: pre/post sqrt(albedo) (d'Eon & Luebke 2007); 0: post-scatter
  vec3 phase_g;             // the Henyey–Greenstein g (S(1), shading.glsl)
  float unused;
  vec4 variances[SSS_MAX_GAUSSIANS / 4];  // v_i in mm^2, ascending
  vec4 gauss_weights[SSS_MAX_GAUSSIANS];  // rgb w_i (sum = T)
  vec4 taps[SSS_MAX_TAPS];                // rgb weight (sum 1), w offset in mm
};

// Push constants.
struct DrawPush {  // G-buffer and shadow draws (view_proj comes from the uniforms)
  mat4 model;
  vec4 material;    // x material index, y light index (shadow draws), z 0 (unused:
                    // roughness reaches lighting through GpuMaterial::roughness), w the
                    // texture path's object index (its irradiance atlas; -1 elsewhere)
  vec4 base_color;  // linear RGBA factor
  vec4 textures;    // x base colour slot, y normal map slot (-1: none), z normal scale
};

struct BlurPush {  // screen-space SSS passes
  vec4 direction;  // xy pixel direction (1,0) or (0,1); z Gaussian index; w 1 = first
};

struct TexturePush {  // texture-space SSS blur (sss_texture.comp)
  vec4 direction;  // xy texel direction (1,0) = u or (0,1) = v; z Gaussian index; w material
};

struct DebugPush {  // debug view pass (debug_view.comp)
  vec4 view;  // x DebugView index; y, z the heat map's low and high ends in the view's
              // unit (Renderer::debug_range(): kernel-radius pixels, thickness mm,
              // uv-stretch mm per unit of UV); w unused
};

#ifdef __cplusplus
static_assert(sizeof(mat4) == 64);
static_assert(sizeof(FrameUniforms) == 3 * 64 + 7 * 16);
static_assert(sizeof(GpuLight) == 2 * 64 + 5 * 16);
static_assert(sizeof(vec3) == 12);
static_assert(sizeof(GpuMaterial) == 16 * (7 + SSS_MAX_GAUSSIANS / 4 + SSS_MAX_GAUSSIANS + SSS_MAX_TAPS));
// The rows of std430: a vec3 at a multiple of 16, its scalar 12 bytes on.
static_assert(offsetof(GpuMaterial, total_reflectance) == 16 && offsetof(GpuMaterial, scatters) == 28);
static_assert(offsetof(GpuMaterial, slab_transmittance) == 32 && offsetof(GpuMaterial, eta) == 48);
static_assert(offsetof(GpuMaterial, exit_norm) == 64 && offsetof(GpuMaterial, range_mm) == 76);
static_assert(offsetof(GpuMaterial, single_albedo) == 80 && offsetof(GpuMaterial, phase_g) == 96);
static_assert(offsetof(GpuMaterial, variances) == 112);
static_assert(sizeof(DrawPush) == 112);
inline constexpr uint kMaxTextures = SSS_MAX_TEXTURES;
inline constexpr uint kMaxLights = SSS_MAX_LIGHTS;
inline constexpr uint kMaxTaps = SSS_MAX_TAPS;
inline constexpr uint kMaxMaterials = SSS_MAX_MATERIALS;
inline constexpr uint kMaxTextureObjects = SSS_MAX_TEXTURE_OBJECTS;
}  // namespace sss::shader
#endif

#endif  // SSS_SHADERS_SHARED_FRAME_H
