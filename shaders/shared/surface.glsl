// A mesh surface's inputs as the G-buffer and the texture path's irradiance raster see
// them (gbuffer_main.glsl, texture_irradiance.frag): the frame uniforms, the material
// textures, the draw's push constants, the interpolated vertex attributes, and the
// shading normal and base colour they give. Not shared with C++.
#ifndef SSS_SHADERS_SURFACE_GLSL
#define SSS_SHADERS_SURFACE_GLSL

#include "frame.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D textures[SSS_MAX_TEXTURES];
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 5) in float in_thickness;  // world units (mesh_vertex.glsl)

#ifdef SSS_SKY_OCCLUSION
// The environment's irradiance that the scene blocks at this point, E_blocked =
// sum_k environment[k] T_k with the interpolated per-vertex transfer T
// (reference/SkyOcclusion.h; exactly 0 where the vertices see the whole sky). The
// lighting subtracts it from the harmonics' unoccluded irradiance (shading.glsl).
layout(set = 0, binding = 2) uniform Lights { LightBlock light_block; };
layout(location = 6) in vec3 in_sky[3];
vec3 sky_blocked() {
  vec3 e = vec3(0.0);
  for (int k = 0; k < 9; ++k) e += light_block.environment[k].rgb * in_sky[k / 3][k % 3];
  return e;
}
#endif

// The inward thickness in mm, what the G-buffer's normal target keeps in w (the
// environment's transmission, shading.glsl); infinite (in half floats) where there is none.
float thickness_mm() { return in_thickness * frame.scale.x; }

// The interpolated normal times `facing` (+-1), bent by the tangent-space normal map
// (glTF: linear, +Y up in UV space, xy scaled) when the draw has one and the mesh has
// tangents.
vec3 shading_normal(float facing) {
  vec3 n = normalize(in_normal) * facing;
  int normal_slot = int(draw.textures.y);
  if (normal_slot >= 0 && dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
    vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
    vec3 b = cross(n, t) * in_tangent.w * facing;
    vec3 m = texture(textures[normal_slot], in_uv).xyz * 2.0 - 1.0;
    m.xy *= draw.textures.z;
    n = normalize(t * m.x + b * m.y + n * max(m.z, 1e-4));
  }
  return n;
}

// Base colour factor x base colour texture (an sRGB view: linear), clamped to [0, 1].
vec3 base_colour() {
  vec3 base = draw.base_color.rgb;
  int base_slot = int(draw.textures.x);
  if (base_slot >= 0) base *= texture(textures[base_slot], in_uv).rgb;
  return clamp(base, 0.0, 1.0);
}

#endif
