#version 460
#extension GL_GOOGLE_include_directive : require
// Texture path, irradiance raster (d'Eon & Luebke 2007, GPU Gems 3 ch. 14): per atlas
// texel, the diffuse irradiance E of the surface point it holds, with the screen path's
// lights, shadow maps and transmission (shared/shading.glsl), and the stretch: mm of
// surface per texel along u and along v. The target's x is u and y is v, so the screen
// derivatives of the world position ARE dP/du and dP/dv per texel (exact: a triangle is
// affine in UV). The normal is the mesh's own (no viewer to face).
#include "shared/surface.glsl"
#include "shared/common.glsl"

layout(set = 0, binding = 2) uniform Lights { LightBlock light_block; };
layout(set = 0, binding = 3) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 4) uniform sampler2DArrayShadow shadow_tex;
layout(set = 0, binding = 5) uniform sampler2DArray shadow_depth_tex;

layout(location = 4) flat in float in_island;
// rgb E, alpha the UV island + 1 (exact in half floats up to 2048: islands wrap there),
// 0 where no triangle covers the texel.
layout(location = 0) out vec4 out_irradiance;
// x mm per texel along u, y along v; alpha 1 where covered.
layout(location = 1) out vec4 out_stretch;

#include "shared/thickness.glsl"
#include "shared/shading.glsl"

void main() {
  SurfacePoint s;
  s.id = int(draw.material.x);
  s.P = in_world;
  s.N = shading_normal(1.0);
  s.V = s.N;  // no specular here
  s.albedo = base_colour();
  vec3 E, S;
  shade(s, false, E, S);
  out_irradiance = vec4(E, mod(in_island, 2048.0) + 1.0);
  out_stretch = vec4(length(dFdx(in_world)) * frame.scale.x, length(dFdy(in_world)) * frame.scale.x,
                     0.0, 1.0);
}
