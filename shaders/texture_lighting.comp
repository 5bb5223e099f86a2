#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, irradiance: per covered atlas texel, the diffuse irradiance E of its
// surface point with the screen path's lights, shadow maps and transmission
// (shared/shading.glsl), and its UV island + 1 in alpha (exact in half floats up to 2048:
// islands wrap there); 0 on empty texels.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform Lights { LightBlock light_block; };
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D position_tex;  // world xyz, w island + 1
layout(set = 0, binding = 4) uniform sampler2D normal_tex;
layout(set = 0, binding = 5) uniform sampler2D albedo_tex;
layout(set = 0, binding = 6) uniform sampler2DArrayShadow shadow_tex;
layout(set = 0, binding = 7) uniform sampler2DArray light_depth_tex;
// In: the raster's sky target (the environment's irradiance the scene blocks, rgb) when
// frame.flags.z is 2 (texture_irradiance_sky.frag drew it); out: E + island.
layout(set = 0, binding = 8, rgba16f) uniform image2D irradiance_img;
layout(push_constant) uniform Push { TexturePush push; };  // w: the material

#include "shared/thickness.glsl"
#include "shared/shading.glsl"

void main() {
  ivec2 size = textureSize(position_tex, 0);
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, size))) return;
  vec4 position = texelFetch(position_tex, p, 0);
  if (position.w < 0.5) {
    imageStore(irradiance_img, p, vec4(0.0));
    return;
  }
  SurfacePoint s;
  s.id = int(push.direction.w);
  s.P = position.xyz;
  vec4 normal = texelFetch(normal_tex, p, 0);
  s.N = normalize(normal.xyz);
  s.thickness_mm = normal.w;
  s.sky_blocked = frame.flags.z > 1.5 ? imageLoad(irradiance_img, p).rgb : vec3(0.0);
  s.V = s.N;  // no specular here
  s.albedo = texelFetch(albedo_tex, p, 0).rgb;
  vec3 E, S;
  shade(s, false, E, S);
  imageStore(irradiance_img, p, vec4(E, mod(position.w - 1.0, 2048.0) + 1.0));
}
