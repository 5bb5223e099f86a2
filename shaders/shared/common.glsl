// GLSL helpers of the screen passes (not shared with C++).
#ifndef SSS_SHADERS_COMMON_GLSL
#define SSS_SHADERS_COMMON_GLSL

const float kPi = 3.14159265358979;

// Material index from the G-buffer's albedo alpha; -1 for background.
int material_id(vec4 albedo_id) { return int(round(albedo_id.a * 255.0)) - 1; }

vec2 pixel_ndc(vec2 pixel_center, vec4 viewport) { return pixel_center * viewport.zw * 2.0 - 1.0; }

// Directional Fresnel (issue 18 part 1; Jensen et al. 2001's separable BSSRDF,
// S_d = F_t(η, ωi) R(r) F_t(η, ωo) / (c π)): the transmittance 1 - Fr of a smooth
// dielectric for light meeting a medium of index eta (per channel) from outside at cosine
// cos_o; by reciprocity also the transmittance of light leaving into cos_o (C++:
// profiles::fresnel_transmittance, the same equations).
vec3 fresnel_transmittance(float cos_o, vec3 eta) {
  float c = clamp(cos_o, 1e-6, 1.0);
  vec3 cos_t = sqrt(max(1.0 - (1.0 - c * c) / (eta * eta), vec3(0.0)));
  vec3 rs = (c - eta * cos_t) / (c + eta * cos_t);
  vec3 rp = (eta * c - cos_t) / (eta * c + cos_t);
  return 1.0 - 0.5 * (rs * rs + rp * rp);
}

#endif
