#version 460
#extension GL_GOOGLE_include_directive : require
// Lighting: per pixel, diffuse irradiance E (before albedo) and GGX specular radiance,
// to separate targets. Only E scatters. E also carries the light transmitted through
// thin parts (shared/shading.glsl, also used by the texture path), so the SSS passes
// spread it with no extra
// pass.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform Lights { LightBlock light_block; };
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D depth_tex;
layout(set = 0, binding = 4) uniform sampler2D normal_tex;
layout(set = 0, binding = 5) uniform sampler2D albedo_tex;
layout(set = 0, binding = 6) uniform sampler2DArrayShadow shadow_tex;
// rgb E, alpha the surface key (sss.glsl) for the separable SSS pass.
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D irradiance_img;
// rgb specular radiance, alpha N·V (the composite's Fresnel exit factor).
layout(set = 0, binding = 8, rgba16f) uniform writeonly image2D specular_img;
// For the SSS passes: x distance from the camera plane in mm, y material id (-1: none).
layout(set = 0, binding = 9, rgba32f) uniform writeonly image2D surface_img;
// The shadow maps read as depth (no comparison, nearest): thickness for transmission.
layout(set = 0, binding = 10) uniform sampler2DArray light_depth_tex;
// The environment's split-sum tables (renderer/EnvironmentMaps.h), read with texelFetch.
layout(set = 0, binding = 11) uniform sampler2DArray environment_specular_tex;
layout(set = 0, binding = 12) uniform sampler2D dfg_tex;
// The G-buffer's sky target: the environment's irradiance the scene blocks (rgb), read
// when frame.flags.z is 2 (gbuffer_sky.frag drew it).
layout(set = 0, binding = 13) uniform sampler2D sky_blocked_tex;
#define SSS_ENVIRONMENT_SPECULAR 1

#include "shared/sss.glsl"
#include "shared/thickness.glsl"
#include "shared/shading.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(frame.rect.xy);  // the geometry's rect
  if (any(greaterThanEqual(p, ivec2(frame.rect.zw)))) return;
  int id = material_id(texelFetch(albedo_tex, p, 0));
  if (id < 0) {
    imageStore(irradiance_img, p, vec4(0.0, 0.0, 0.0, kBackgroundKey));
    imageStore(specular_img, p, vec4(0.0));
    imageStore(surface_img, p, vec4(0.0, -1.0, 0.0, 0.0));
    return;
  }
  float depth = texelFetch(depth_tex, p, 0).r;
  vec4 w = frame.inv_view_proj * vec4(pixel_ndc(vec2(p) + 0.5, frame.viewport), depth, 1.0);
  SurfacePoint s;
  s.id = id;
  s.P = w.xyz / w.w;
  vec4 normal = texelFetch(normal_tex, p, 0);
  s.N = normalize(normal.xyz);
  s.thickness_mm = normal.w;
  s.sky_blocked = frame.flags.z > 1.5 ? texelFetch(sky_blocked_tex, p, 0).rgb : vec3(0.0);
  s.V = frame.camera.w > 0.5 ? -frame.forward.xyz : normalize(frame.camera.xyz - s.P);
  s.albedo = texelFetch(albedo_tex, p, 0).rgb;
  float depth_mm = dot(s.P - frame.camera.xyz, frame.forward.xyz) * frame.scale.x;
  imageStore(surface_img, p, vec4(depth_mm, float(id), 0.0, 0.0));
  vec3 E, S;
  shade(s, true, E, S);
  imageStore(irradiance_img, p, vec4(E, surface_key(id, depth_mm)));
  // alpha: N·V, the cosine the composite's Fresnel exit factor needs (composite.glsl).
  imageStore(specular_img, p, vec4(S, clamp(dot(s.N, s.V), 0.0, 1.0)));
}
