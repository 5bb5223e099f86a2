// The composite of one surface pixel (composite.comp, and the separable SSS pass's
// vertical half, which composites the pixels it scatters): linear radiance and its
// display code. Not shared with C++.
#ifndef SSS_SHADERS_COMPOSITE_GLSL
#define SSS_SHADERS_COMPOSITE_GLSL

// Needs: frame (FrameUniforms), materials (GpuMaterial[]), common.glsl.

#include "tonemap.h"

// Narkowicz's fit of the ACES filmic curve.
vec3 filmic(vec3 x) { return clamp(SSS_FILMIC_CURVE(x), 0.0, 1.0); }
vec3 srgb_encode(vec3 c) {
  return mix(c * SSS_SRGB_LINEAR_SLOPE, SSS_SRGB_SCALE * pow(c, vec3(1.0 / SSS_SRGB_GAMMA)) - SSS_SRGB_OFFSET,
             greaterThan(c, vec3(SSS_SRGB_ENCODE_CUTOFF)));
}
// The display image's value for linear radiance L: exposure, filmic, sRGB encoding.
vec3 display_encode(vec3 L) { return srgb_encode(filmic(L * frame.scale.w)); }

// The diffuse light R * E of a subsurface pixel (before albedo) in the techniques whose
// result is in the accum target: gaussians always, texture where its lookup wrote
// (alpha 1; an object left out of texture space has no spread); `local` (R * E at the
// pixel, no spread) otherwise.
vec3 scattered_diffuse(vec3 local, vec4 accumulated) {
  int technique = int(frame.options.y);
  if (technique == SSS_TECHNIQUE_GAUSSIANS ||
      (technique == SSS_TECHNIQUE_TEXTURE && accumulated.a > 0.5))
    return accumulated.rgb;
  return local;
}

// Whether the frame's technique has its result in the accum target. Read accum only then:
// the other techniques leave it 1 x 1 (FrameTargets::Use).
bool accumulates() {
  int technique = int(frame.options.y);
  return technique == SSS_TECHNIQUE_GAUSSIANS || technique == SSS_TECHNIQUE_TEXTURE;
}

// The exit factor of a subsurface pixel seen at cosine NdotV (lighting.comp stores it in
// the specular target's alpha): F_t(η, θo) / c with directional Fresnel, the exitance
// leaving in the normalised Fresnel lobe instead of Lambert's (∫ F_t cos / (c π) dω = 1,
// so no energy is made or lost; profiles::fresnel_exit_normalization); 1 otherwise.
vec3 exit_fresnel(int id, float NdotV) {
  if (frame.flags.x < 0.5 || materials[id].scatters == 0) return vec3(1.0);
  return fresnel_transmittance(NdotV, materials[id].eta) * materials[id].exit_norm;
}

// L = albedo (1 - metallic) diffuse x exit / pi + specular.rgb, where diffuse is R * E
// (scattered or local) or E (Lambert) and exit the Fresnel exit factor at cosine
// specular.a (exit_fresnel); pre/post albedo takes the second sqrt(albedo) here.
vec3 composite_radiance(int id, vec3 albedo, vec3 diffuse, vec4 specular) {
  float metallic = materials[id].metallic;  // not the whole GpuMaterial
  vec3 a = materials[id].pre_post != 0 ? sqrt(albedo) : albedo;
  return a * (1.0 - metallic) * diffuse * exit_fresnel(id, specular.a) / kPi + specular.rgb;
}

#endif
