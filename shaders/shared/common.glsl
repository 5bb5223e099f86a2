// GLSL helpers of the screen passes (not shared with C++).
#ifndef SSS_SHADERS_COMMON_GLSL
#define SSS_SHADERS_COMMON_GLSL

const float kPi = 3.14159265358979;

// Material index from the G-buffer's albedo alpha; -1 for background.
int material_id(vec4 albedo_id) { return int(round(albedo_id.a * 255.0)) - 1; }

vec2 pixel_ndc(vec2 pixel_center, vec4 viewport) { return pixel_center * viewport.zw * 2.0 - 1.0; }

// An equirectangular layer of `tex` at direction d (unit), bilinear between texel centres
// with texelFetch: u wraps, v clamps (scene::equirect_bilinear, scene/Environment.h's
// convention: u = 1/2 + atan2(d.x, -d.z) / 2 pi, v = acos(d.y) / pi).
vec3 equirect_bilinear(sampler2DArray tex, int layer, vec3 d) {
  ivec2 size = textureSize(tex, 0).xy;
  // atan(0, 0) is undefined in GLSL: straight up or down, u = 1/2 (as in C++).
  float u = (d.x == 0.0 && d.z == 0.0) ? 0.5 : 0.5 + atan(d.x, -d.z) / (2.0 * kPi);
  float v = acos(clamp(d.y, -1.0, 1.0)) / kPi;
  float fx = u * float(size.x) - 0.5;
  float fy = clamp(v * float(size.y) - 0.5, 0.0, float(size.y - 1));
  int x0 = int(floor(fx)), y0 = int(floor(fy));
  float tx = fx - float(x0), ty = fy - float(y0);
  int xa = (x0 + size.x) % size.x, xb = (x0 + 1 + size.x) % size.x;  // x0 >= -1
  int ya = y0, yb = min(y0 + 1, size.y - 1);
  vec3 top = texelFetch(tex, ivec3(xa, ya, layer), 0).rgb * (1.0 - tx) +
             texelFetch(tex, ivec3(xb, ya, layer), 0).rgb * tx;
  vec3 bottom = texelFetch(tex, ivec3(xa, yb, layer), 0).rgb * (1.0 - tx) +
                texelFetch(tex, ivec3(xb, yb, layer), 0).rgb * tx;
  return top * (1.0 - ty) + bottom * ty;
}

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
