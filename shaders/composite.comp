#version 460
#extension GL_GOOGLE_include_directive : require
// Composite: post-scatter albedo (or the second sqrt(albedo) of pre/post) x scattered
// irradiance / pi + specular (linear HDR), and
// the display image (exposure, filmic tonemap, sRGB encoding; alpha 0 where there is no
// geometry, so PNG comparisons can mask the background).
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 2) uniform sampler2D albedo_tex;
layout(set = 0, binding = 3) uniform sampler2D irradiance_tex;
layout(set = 0, binding = 4) uniform sampler2D specular_tex;
layout(set = 0, binding = 5) uniform sampler2D scattered_tex;    // separable: K * E
layout(set = 0, binding = 6) uniform sampler2D accumulated_tex;  // gaussians: R * E
layout(set = 0, binding = 7, rgba32f) uniform writeonly image2D hdr_img;
layout(set = 0, binding = 8, rgba8) uniform writeonly image2D display_img;

// Narkowicz's fit of the ACES filmic curve.
vec3 filmic(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}
vec3 srgb_encode(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  vec4 albedo_id = texelFetch(albedo_tex, p, 0);
  int id = material_id(albedo_id);
  vec3 L = vec3(0.0);
  float alpha = 0.0;
  if (id >= 0) {
    vec4 reflectance = materials[id].reflectance;  // not the whole GpuMaterial
    float metallic = materials[id].surface.y;
    vec3 E = texelFetch(irradiance_tex, p, 0).rgb;
    vec3 diffuse;
    int mode = int(frame.options.y);
    if (reflectance.w > 0.5) {
      if (mode == 1)
        diffuse = reflectance.rgb * texelFetch(scattered_tex, p, 0).rgb;
      else if (mode == 2)
        diffuse = texelFetch(accumulated_tex, p, 0).rgb;
      else
        diffuse = reflectance.rgb * E;  // no spread: the total reflectance, locally
    } else {
      diffuse = E;  // Lambert
    }
    vec3 albedo = materials[id].kernel.z > 0.5 ? sqrt(albedo_id.rgb) : albedo_id.rgb;
    L = albedo * (1.0 - metallic) * diffuse / kPi + texelFetch(specular_tex, p, 0).rgb;
    alpha = 1.0;
  }
  imageStore(hdr_img, p, vec4(L, alpha));
  imageStore(display_img, p, vec4(srgb_encode(filmic(L * frame.scale.w)), alpha));
}
