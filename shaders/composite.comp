#version 460
#extension GL_GOOGLE_include_directive : require
// Composite: post-scatter albedo (or the second sqrt(albedo) of pre/post) x scattered
// irradiance / pi + specular (linear HDR), and
// the display image (exposure, filmic tonemap, sRGB encoding; alpha 0 where there is no
// geometry, so PNG comparisons can mask the background). In separable mode the SSS
// pass's vertical half has already composited the pixels it scattered (composite.glsl);
// they are left alone here.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D albedo_tex;
layout(set = 0, binding = 3) uniform sampler2D irradiance_tex;
layout(set = 0, binding = 4) uniform sampler2D specular_tex;
layout(set = 0, binding = 6) uniform sampler2D accumulated_tex;  // gaussians: R * E
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D hdr_img;
layout(set = 0, binding = 8, rgba8) uniform writeonly image2D display_img;
// The environment's radiance, equirectangular (EnvironmentMaps::background).
layout(set = 0, binding = 9) uniform sampler2DArray background_tex;

#include "shared/composite.glsl"

// The environment's radiance seen through pixel p: the view ray from two points of the
// pixel's line of sight (reversed depth: 1 at the near plane; 0.5 is finite even with an
// infinite far plane), which serves perspective and orthographic cameras alike.
vec3 background_radiance(ivec2 p) {
  vec2 ndc = pixel_ndc(vec2(p) + 0.5, frame.viewport);
  vec4 a = frame.inv_view_proj * vec4(ndc, 1.0, 1.0);
  vec4 b = frame.inv_view_proj * vec4(ndc, 0.5, 1.0);
  return equirect_bilinear(background_tex, 0, normalize(b.xyz / b.w - a.xyz / a.w));
}

void main() {
  // The geometry's rect, or every pixel when the environment is behind the geometry.
  bool environment_behind = frame.flags.w > 0.5;
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + (environment_behind ? ivec2(0) : ivec2(frame.rect.xy));
  if (any(greaterThanEqual(p, environment_behind ? ivec2(frame.viewport.xy) : ivec2(frame.rect.zw))))
    return;
  bool in_rect = all(greaterThanEqual(p, ivec2(frame.rect.xy))) && all(lessThan(p, ivec2(frame.rect.zw)));
  vec4 albedo_id = in_rect ? texelFetch(albedo_tex, p, 0) : vec4(0.0);
  int id = material_id(albedo_id);
  if (id < 0) {  // background: hdr and display were cleared (Renderer::record)
    if (environment_behind) imageStore(display_img, p, vec4(display_encode(background_radiance(p)), 1.0));
    return;
  }
  bool scatters = materials[id].scatters != 0;  // not the whole GpuMaterial
  int technique = int(frame.options.y);
  if (scatters && technique == SSS_TECHNIQUE_SEPARABLE) return;  // sss_separable.comp wrote it
  vec3 E = texelFetch(irradiance_tex, p, 0).rgb;
  vec3 diffuse;
  if (scatters) {
    vec4 accumulated = vec4(0.0);
    if (accumulates()) accumulated = texelFetch(accumulated_tex, p, 0);
    diffuse = scattered_diffuse(materials[id].total_reflectance * E, accumulated);
  } else {
    diffuse = E;  // Lambert
  }
  vec3 L = composite_radiance(id, albedo_id.rgb, diffuse, texelFetch(specular_tex, p, 0));
  imageStore(hdr_img, p, vec4(L, 1.0));
  imageStore(display_img, p, vec4(display_encode(L), 1.0));
}
