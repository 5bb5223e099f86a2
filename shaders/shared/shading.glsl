// Direct lighting of one surface point, shared by the screen path (lighting.comp, per
// pixel) and the texture path (texture_lighting.comp, per atlas texel): diffuse
// irradiance E (before albedo, with the light transmitted through thin parts) and GGX
// specular radiance. Not shared with C++.
#ifndef SSS_SHADERS_SHADING_GLSL
#define SSS_SHADERS_SHADING_GLSL

// Needs: frame (FrameUniforms), light_block (LightBlock), materials (GpuMaterial[]),
// shadow_tex (sampler2DArrayShadow), light_depth_tex (sampler2DArray, nearest: the unbiased depth for thickness),
// common.glsl, thickness.glsl.

// Transmission (DESIGN.md §5 step 5; Jimenez, Whelan, Sundstedt & Gutierrez 2010,
// "Real-Time Realistic Skin Translucency", IEEE CG&A 30(4)): light entering the far
// side at the shadow map's first surface crosses the thickness d (mm) and leaves at P.
// A point source at depth d below the surface gives R(sqrt(r² + d²)) at lateral distance
// r on it; for the fit R(r) = Σ w_i G(v_i, r) that is Σ w_i exp(-d²/2v_i) G(v_i, r), the
// same Gaussians with weights scaled per channel, whose total is
// T(d) = Σ w_i exp(-d²/2v_i). Slabs (slab_thickness_mm > 0) use the
// multipole's own total transmittance instead (transmit.rgb, the fit of its T(r) with the
// same variances). The far side's irradiance is E_back = E_light max(-N·L, 0) (the far
// side faces the light where P faces away from it; Jimenez 2010 uses a wrapped
// 0.3 + (-N·L), we keep the unwrapped one so a slab lit at normal incidence gets exactly
// E_light). The result is added to E divided by the total reflectance Σ w_i: the SSS
// passes blur it with the reflectance profile (Σ w_i G_i, which moves no energy) and the
// composite multiplies by Σ w_i, so the exitant diffuse is T(d) E_back x albedo / pi,
// spread by the reflectance profile's shape rather than the transmitted one (for a
// thickness comparable to the widest Gaussian the transmitted profile is wider).
vec3 transmittance_total(int id, float d_mm) {
  if (materials[id].slab_thickness_mm > 0.0) return materials[id].slab_transmittance;
  vec3 sum = vec3(0.0);
  int count = materials[id].gaussian_count;
  for (int g = 0; g < count; ++g) {
    float v = materials[id].variances[g / 4][g % 4];
    sum += materials[id].gauss_weights[g].rgb * exp(-d_mm * d_mm / (2.0 * v));
  }
  return sum;
}

// The factor light entering a subsurface material at cosine NdotL keeps: F_t with
// directional Fresnel on, 1 (all of it) otherwise.
vec3 entry_fresnel(int id, float NdotL) {
  if (frame.flags.x < 0.5) return vec3(1.0);
  return fresnel_transmittance(NdotL, materials[id].eta);
}

// Henyey–Greenstein phase function, normalised over the sphere (profiles::henyey_greenstein).
float henyey_greenstein(float g, float cos_theta) {
  float d = 1.0 + g * g - 2.0 * g * cos_theta;
  return (1.0 - g * g) / (4.0 * kPi * d * sqrt(d));
}

// Single scattering S(1) (issue 18 part 2): the planar closed form of Hanrahan & Krueger
// 1993 that Jensen et al. 2001 §2.3 use, per channel, for a collimated light along L and
// the eye along V at a surface of normal N:
//   f1 = F_t(η, μi) F_t(η, μo) α p(g, cos θ) / (η² (μi' + μo')),
// μi', μo' the refracted (inside) cosines, θ the angle between the refracted beam's
// travel direction and the inside direction that refracts out along V. L⁽¹⁾ = E μi f1 is
// the once-scattered radiance. C++: profiles::single_scattering_brdf (profiles/
// SingleScattering.h, which says exactly what is integrated; the same equations, checked
// against the analog walk). The F_t factors belong to S(1) itself, whatever --fresnel says.
vec3 single_scattering_brdf(int id, vec3 N, vec3 L, vec3 V) {
  vec3 eta = materials[id].eta;
  vec3 alpha = materials[id].single_albedo;
  vec3 g = materials[id].phase_g;
  float mu_i = clamp(dot(N, L), 1e-4, 1.0);
  float mu_o = clamp(dot(N, V), 1e-4, 1.0);
  vec3 f = vec3(0.0);
  for (int c = 0; c < 3; ++c) {
    vec3 t_in = refract(-L, N, 1.0 / eta[c]);    // the beam, travelling in
    vec3 t_out = -refract(-V, N, 1.0 / eta[c]);  // travelling out, leaves along V
    float mi = max(-dot(t_in, N), 1e-4), mo = max(dot(t_out, N), 1e-4);
    f[c] = alpha[c] * henyey_greenstein(g[c], dot(t_in, t_out)) / (eta[c] * eta[c] * (mi + mo));
  }
  return f * fresnel_transmittance(mu_i, eta) * fresnel_transmittance(mu_o, eta);
}

float shadow_visibility(int index, GpuLight light, vec3 p, vec3 n) {
  vec4 c = light.shadow_matrix * vec4(p + n * light.shadow.z, 1.0);
  vec3 s = c.xyz / c.w;
  vec2 uv = s.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || s.z > 1.0) return 1.0;
  // 3x3 PCF: the mean of 9 bilinear comparison taps one texel apart. Along an axis those
  // weigh the 4 texels i-1 .. i+2 around the point (i = floor(u - 0.5), f its fraction, in
  // texels) by (1 - f, 1, 1, f) / 3, which 2 bilinear taps give exactly: one on texels
  // i-1, i at fraction 1 / (2 - f) with weight (2 - f) / 3, one on i+1, i+2 at fraction
  // f / (1 + f) with weight (1 + f) / 3. So 4 taps instead of 9, the same filter.
  vec2 size = vec2(textureSize(shadow_tex, 0).xy);
  vec2 t = uv * size - 0.5;
  vec2 i = floor(t);
  vec2 f = t - i;
  vec2 w0 = 2.0 - f, w1 = 1.0 + f;
  vec2 p0 = (i - 1.0 + 1.0 / w0 + 0.5) / size;  // texel centres are at k + 0.5
  vec2 p1 = (i + 1.0 + f / w1 + 0.5) / size;
  float ref = s.z - light.shadow.w;
  float layer = float(index);
  float sum = w0.x * w0.y * texture(shadow_tex, vec4(p0.x, p0.y, layer, ref)) +
              w1.x * w0.y * texture(shadow_tex, vec4(p1.x, p0.y, layer, ref)) +
              w0.x * w1.y * texture(shadow_tex, vec4(p0.x, p1.y, layer, ref)) +
              w1.x * w1.y * texture(shadow_tex, vec4(p1.x, p1.y, layer, ref));
  return sum / 9.0;
}

// Light i at P: the unit direction L towards it and its irradiance at normal incidence
// (spot cone and distance falloff applied); false where its half-space mask leaves P dark.
bool light_at(GpuLight light, vec3 P, out vec3 L, out vec3 radiance) {
  L = vec3(0.0, 0.0, 1.0);
  radiance = light.color.rgb;
  if (light.shadow.x > 0.5 && dot(light.mask.xyz, P) + light.mask.w >= 0.0) return false;
  int type = int(light.color.w);
  if (type == SSS_LIGHT_DIRECTIONAL) {
    L = -light.direction.xyz;
  } else {
    vec3 d = light.position.xyz - P;
    float d2 = max(dot(d, d), 1e-8);
    L = d * inversesqrt(d2);
    radiance /= d2;
    if (type == SSS_LIGHT_SPOT)
      radiance *= smoothstep(light.direction.w, light.position.w, dot(-L, light.direction.xyz));
  }
  return true;
}

// The environment's irradiance on a surface of unit normal n that sees the whole sphere
// above it: the 9 coefficients of light_block.environment (C++: scene::Environment::
// irradiance, the same basis), clamped at 0.
vec3 environment_irradiance(vec3 n) {
  float b[9] = float[9](0.282095, 0.488603 * n.y, 0.488603 * n.z, 0.488603 * n.x,
                        1.092548 * n.x * n.y, 1.092548 * n.y * n.z,
                        0.315392 * (3.0 * n.z * n.z - 1.0), 1.092548 * n.x * n.z,
                        0.546274 * (n.x * n.x - n.y * n.y));
  vec3 e = vec3(0.0);
  for (int k = 0; k < 9; ++k) e += light_block.environment[k].rgb * b[k];
  return max(e, vec3(0.0));
}

#ifdef SSS_ENVIRONMENT_SPECULAR
// The environment's specular light by the split sum (C++: scene/SplitSum.h, which
// derives it; the same lookups, in float): Lp(R, r) (F0 A + B). Needs
// environment_specular_tex (sampler2DArray: the prefiltered levels, equirectangular) and
// dfg_tex (sampler2D: A, B over n.v and r at texel centres).

// Bilinear in one level at direction d (unit): u wraps, v clamps (scene::equirect_bilinear).
vec3 environment_level(int layer, vec3 d) { return equirect_bilinear(environment_specular_tex, layer, d); }

// scene::dfg_lookup: (A, B) bilinear between texel centres, clamped at the edges.
vec2 dfg_lookup(float n_dot_v, float roughness) {
  int n = textureSize(dfg_tex, 0).x;
  float x = clamp(n_dot_v * float(n) - 0.5, 0.0, float(n - 1));
  float y = clamp(roughness * float(n) - 0.5, 0.0, float(n - 1));
  int x0 = min(int(x), n - 2), y0 = min(int(y), n - 2);
  float fx = x - float(x0), fy = y - float(y0);
  vec2 a = texelFetch(dfg_tex, ivec2(x0, y0), 0).xy * (1.0 - fx) + texelFetch(dfg_tex, ivec2(x0 + 1, y0), 0).xy * fx;
  vec2 b = texelFetch(dfg_tex, ivec2(x0, y0 + 1), 0).xy * (1.0 - fx) +
           texelFetch(dfg_tex, ivec2(x0 + 1, y0 + 1), 0).xy * fx;
  return a * (1.0 - fy) + b * fy;
}

vec3 environment_specular(vec3 N, vec3 V, float roughness, vec3 F0) {
  int levels = textureSize(environment_specular_tex, 0).z;
  float f = clamp(roughness, 0.0, 1.0) * float(levels - 1);
  int k0 = min(int(f), levels - 2);
  float t = f - float(k0);
  vec3 R = reflect(-V, N);
  vec3 Lp = environment_level(k0, R) * (1.0 - t) + environment_level(k0 + 1, R) * t;
  vec2 ab = dfg_lookup(max(dot(N, V), 1e-4), roughness);
  return Lp * (F0 * ab.x + ab.y);
}
#endif

struct SurfacePoint {
  int id;       // material
  vec3 P;       // world position
  vec3 N;       // unit normal
  vec3 V;       // unit direction to the eye (specular only)
  vec3 albedo;  // base colour (F0 of metals)
  float thickness_mm;  // inward thickness along -N (the G-buffer's), for the sky's transmission
  // The environment's irradiance that the scene blocks here (surface.glsl, sky_blocked;
  // what the G-buffer's sky target holds when frame.flags.z is 2), else 0.
  vec3 sky_blocked;
};

// E: irradiance at P (Σ over lights of E_light N·L x shadow; for subsurface materials
// with directional Fresnel x F_t(η, N·L), the part that enters), plus for subsurface
// materials the transmitted E_back / Σ w_i (see above); S: specular radiance, computed
// only when `specular` is true (the texture path needs E alone), with single scattering
// S(1) added for subsurface materials when it is on (frame.flags.y): Σ E_light N·L x
// shadow x f1 x albedo (1 - metallic), not blurred (the profiles leave it out then,
// profiles::ModelOptions::single_scattering_apart).
void shade(SurfacePoint s, bool specular, out vec3 E, out vec3 S) {
  // The fields, not the whole GpuMaterial: lavapipe would load it all.
  float roughness = materials[s.id].roughness;
  float metallic = materials[s.id].metallic;
  float NdotV = max(dot(s.N, s.V), 1e-4);
  float alpha = max(roughness * roughness, 1e-3);
  float a2 = alpha * alpha;
  vec3 F0 = mix(vec3(materials[s.id].f0), s.albedo, metallic);
  bool has_specular = specular && max(F0.r, max(F0.g, F0.b)) > 0.0;
  E = vec3(0.0);
  S = vec3(0.0);
  vec3 E_back = vec3(0.0);  // x the total transmittance of the thickness, per light
  bool subsurface = materials[s.id].scatters != 0;
  bool transmits = frame.options.w > 0.5 && subsurface;
  bool single = specular && subsurface && frame.flags.y > 0.5;
  vec3 single_tint = s.albedo * (1.0 - metallic);
  int count = int(frame.options.x);
  for (int i = 0; i < count; ++i) {
    GpuLight light = light_block.lights[i];
    vec3 L, radiance;
    if (!light_at(light, s.P, L, radiance)) continue;
    float NdotL = dot(s.N, L);
    if (NdotL <= 0.0) {
      if (transmits && NdotL < 0.0) {
        float d = shadow_thickness(light_depth_tex, i, light, s.P);  // -1: no shadow map
        if (d >= 0.0)
          E_back += radiance * -NdotL * entry_fresnel(s.id, -NdotL) *
                    transmittance_total(s.id, d * frame.scale.x);
      }
      continue;
    }
    float visibility = light.shadow.y > 0.5 ? shadow_visibility(i, light, s.P, s.N) : 1.0;
    vec3 incident = radiance * NdotL * visibility;
    // Subsurface light counts only what crosses the boundary: R(r) is per unit power that
    // entered (docs/ARCHITECTURE.md), the specular lobe takes the rest.
    E += subsurface ? incident * entry_fresnel(s.id, NdotL) : incident;
    if (single) S += incident * single_tint * single_scattering_brdf(s.id, s.N, L, s.V);
    if (has_specular) {
      vec3 H = normalize(L + s.V);
      float NdotH = max(dot(s.N, H), 0.0);
      float VdotH = max(dot(s.V, H), 0.0);
      float dd = NdotH * NdotH * (a2 - 1.0) + 1.0;
      float D = a2 / (kPi * dd * dd);
      float vis = 0.5 / (NdotL * sqrt(NdotV * NdotV * (1.0 - a2) + a2) +
                         NdotV * sqrt(NdotL * NdotL * (1.0 - a2) + a2));
      vec3 F = F0 + (1.0 - F0) * pow(1.0 - VdotH, 5.0);
      S += D * vis * F * incident;
    }
  }
  // The environment (frame.flags.z): its irradiance from the spherical harmonics less
  // what the scene blocks (s.sky_blocked: the per-vertex transfer of reference/
  // SkyOcclusion.h, zero on a surface that sees the whole sky; clamped at 0 where a normal
  // map turns N away from the vertex normal the bake used); with directional Fresnel, a subsurface material takes the part of it that
  // enters, c = the cosine-weighted mean of F_t over the hemisphere (1 / exit_norm; exact
  // for a uniform sky, which the GPU cannot tell from others); its specular by the split
  // sum where the pass has the tables (lighting.comp).
  // Its transmission: the sky lights the far side of a thin part from every direction, so
  // no one light's shadow map gives the path. The surface behind P is taken d = the inward
  // thickness away along -N, facing -N: it receives environment_irradiance(-N) (entering
  // by the same c), which crosses d as a light's does, T(d) (transmittance_total; a slab's
  // own total). Exact for a flat slab under any sky; on a curved thin part the far
  // surface's normal and its distance vary over the profile's width.
  if (frame.flags.z > 0.5) {
    vec3 sky = max(environment_irradiance(s.N) - s.sky_blocked, vec3(0.0));
    bool entering = subsurface && frame.flags.x > 0.5;
    if (entering) sky /= materials[s.id].exit_norm;
    E += sky;
    if (transmits && s.thickness_mm >= 0.0 && s.thickness_mm < 1e30) {
      vec3 behind = environment_irradiance(-s.N);
      if (entering) behind /= materials[s.id].exit_norm;
      E_back += behind * transmittance_total(s.id, s.thickness_mm);
    }
#ifdef SSS_ENVIRONMENT_SPECULAR
    if (has_specular) S += environment_specular(s.N, s.V, roughness, F0);
#endif
  }
  if (transmits) E += E_back / max(materials[s.id].total_reflectance, vec3(1e-6));
  // Pre/post albedo: sqrt(albedo) enters before scattering, the other half after it.
  if (materials[s.id].pre_post != 0) E *= sqrt(s.albedo);
}

// S(1) alone at a subsurface point, as shade() adds it to S with single scattering on (the
// debug view "single scattering" shows it whatever the switch says).
vec3 single_scattering_radiance(SurfacePoint s) {
  vec3 sum = vec3(0.0);
  int count = int(frame.options.x);
  for (int i = 0; i < count; ++i) {
    GpuLight light = light_block.lights[i];
    vec3 L, radiance;
    if (!light_at(light, s.P, L, radiance)) continue;
    float NdotL = dot(s.N, L);
    if (NdotL <= 0.0) continue;
    float visibility = light.shadow.y > 0.5 ? shadow_visibility(i, light, s.P, s.N) : 1.0;
    sum += radiance * NdotL * visibility * single_scattering_brdf(s.id, s.N, L, s.V);
  }
  return sum * s.albedo * (1.0 - materials[s.id].metallic);
}

#endif
