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

#include "shared/composite.glsl"

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + ivec2(frame.rect.xy);  // the geometry's rect
  if (any(greaterThanEqual(p, ivec2(frame.rect.zw)))) return;
  vec4 albedo_id = texelFetch(albedo_tex, p, 0);
  int id = material_id(albedo_id);
  if (id < 0) return;  // background: hdr and display were cleared to 0 (Renderer::record)
  vec4 reflectance = materials[id].reflectance;  // not the whole GpuMaterial
  int mode = int(frame.options.y);
  if (reflectance.w > 0.5 && mode == 1) return;  // sss_separable.comp wrote it
  vec3 E = texelFetch(irradiance_tex, p, 0).rgb;
  vec3 diffuse;
  if (reflectance.w > 0.5) {
    diffuse = scattered_diffuse(reflectance.rgb * E, texelFetch(accumulated_tex, p, 0));
  } else {
    diffuse = E;  // Lambert
  }
  vec3 L = composite_radiance(id, albedo_id.rgb, diffuse, texelFetch(specular_tex, p, 0));
  imageStore(hdr_img, p, vec4(L, 1.0));
  imageStore(display_img, p, vec4(display_encode(L), 1.0));
}
