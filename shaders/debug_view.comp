#version 460
#extension GL_GOOGLE_include_directive : require
// Debug views (RenderOptions::debug_view, renderer/README.md): after composite, the display
// image shows one intermediate of the frame instead of the shaded frame; the HDR image
// keeps the shaded frame. Recorded only when a view is asked for, so the frame without one
// pays nothing. Background: 0 (alpha 0) as in the frame.
#include "shared/frame.h"
#include "shared/common.glsl"

layout(local_size_x = SSS_WORKGROUP_2D_X, local_size_y = SSS_WORKGROUP_2D_Y) in;

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform Lights { LightBlock light_block; };
layout(set = 0, binding = 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(set = 0, binding = 3) uniform sampler2D albedo_tex;
layout(set = 0, binding = 4) uniform sampler2D depth_tex;
layout(set = 0, binding = 5) uniform sampler2D irradiance_tex;  // rgb E, a surface key
layout(set = 0, binding = 6) uniform sampler2D specular_tex;
layout(set = 0, binding = 7) uniform sampler2D scattered_tex;    // separable: R * E
layout(set = 0, binding = 8) uniform sampler2D accumulated_tex;  // gaussians: R * E
layout(set = 0, binding = 9) uniform sampler2DArray light_depth_tex;  // no comparison
layout(set = 0, binding = 10) uniform sampler2D uv_stretch_tex;  // mm per u, v; has UVs
layout(set = 0, binding = 11, rgba8) uniform writeonly image2D display_img;
layout(set = 0, binding = 12) uniform sampler2D normal_tex;             // single scattering
layout(set = 0, binding = 13) uniform sampler2DArrayShadow shadow_tex;  // single scattering
layout(push_constant) uniform Push { DebugPush debug; };

#include "shared/composite.glsl"
#include "shared/sss.glsl"
#include "shared/thickness.glsl"
#include "shared/shading.glsl"

// A fit of matplotlib's viridis (Matt Zucker, CC0): t in [0, 1] -> display colour.
vec3 viridis(float t) {
  const vec3 c0 = vec3(0.2777273272234177, 0.005407344544966578, 0.3340998053353061);
  const vec3 c1 = vec3(0.1050930431085774, 1.404613529898575, 1.384590162594685);
  const vec3 c2 = vec3(-0.3308618287255563, 0.214847559468213, 0.09509516302823659);
  const vec3 c3 = vec3(-4.634230498983486, -5.799100973351585, -19.33244095627987);
  const vec3 c4 = vec3(6.228269936347081, 14.17993336680509, 56.69055260068105);
  const vec3 c5 = vec3(4.776384997670288, -13.74514537774601, -65.35303263337234);
  const vec3 c6 = vec3(-5.435455855934631, 4.645852612178535, 26.3124352495832);
  t = clamp(t, 0.0, 1.0);
  return clamp(c0 + t * (c1 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * c6))))), 0.0, 1.0);
}

const vec3 kNoValue = vec3(0.25);          // grey: the view has no value at this pixel
const vec3 kUndersampled = vec3(1.0, 0.0, 1.0);  // magenta: kernel radius below 1 pixel

// One flat, distinct colour per material id (golden-ratio hue steps).
vec3 id_colour(int id) {
  float h = fract(0.13 + float(id) * 0.6180339887);
  vec3 k = clamp(abs(fract(h + vec3(0.0, 2.0 / 3.0, 1.0 / 3.0)) * 6.0 - 3.0) - 1.0, 0.0, 1.0);
  return mix(vec3(1.0), k, 0.8) * (id % 2 == 0 ? 0.95 : 0.7);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  int id = material_id(texelFetch(albedo_tex, p, 0));
  if (id < 0) return;  // background: display was cleared to 0 (Renderer::record)
  int view = int(debug.view.x);
  bool scatters = materials[id].scatters != 0;
  vec4 irradiance = texelFetch(irradiance_tex, p, 0);
  vec3 E = irradiance.rgb;
  vec3 c = kNoValue;
  if (view == 1) {  // irradiance
    c = display_encode(E / kPi);
  } else if (view == 2) {  // specular
    c = display_encode(texelFetch(specular_tex, p, 0).rgb);
  } else if (view == 3) {  // scattered diffuse, before albedo
    int technique = int(frame.options.y);
    vec3 diffuse = E;  // Lambert
    if (scatters) {
      if (technique == SSS_TECHNIQUE_SEPARABLE) {
        diffuse = texelFetch(scattered_tex, p, 0).rgb;
      } else {
        vec4 accumulated = vec4(0.0);
        if (accumulates()) accumulated = texelFetch(accumulated_tex, p, 0);
        diffuse = scattered_diffuse(materials[id].total_reflectance * E, accumulated);
      }
    }
    c = display_encode(diffuse / kPi);
  } else if (view == 4) {  // kernel radius in pixels
    if (scatters) {
      // The kernel's reach as the blur lays it out (sss.glsl): along each axis the camera
      // plane's pixels per mm over the surface's foreshortening; the shorter of the two.
      float z = key_depth(irradiance.a, id);
      ivec2 hi = textureSize(irradiance_tex, 0) - 1;
      float radius_px = 1e30;
      for (int axis = 0; axis < 2; ++axis) {
        vec2 dir = axis == 0 ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
        ivec2 step = ivec2(dir);
        float ppm = pixels_per_mm(dir, z);
        float slope = key_depth_slope(texelFetch(irradiance_tex, clamp(p - step, ivec2(0), hi), 0).a,
                                      texelFetch(irradiance_tex, clamp(p + step, ivec2(0), hi), 0).a, id, z, ppm);
        radius_px = min(radius_px, materials[id].range_mm * ppm / foreshortening(slope));
      }
      float log_lo = log2(debug.view.y), log_hi = log2(debug.view.z);
      c = radius_px < 1.0 ? kUndersampled : viridis((log2(radius_px) - log_lo) / (log_hi - log_lo));
    }
  } else if (view == 5) {  // profile / material id
    c = id_colour(id);
  } else if (view == 6) {  // thickness along light 0
    float depth = texelFetch(depth_tex, p, 0).r;
    vec4 w = frame.inv_view_proj * vec4(pixel_ndc(vec2(p) + 0.5, frame.viewport), depth, 1.0);
    float t = int(frame.options.x) > 0
                  ? shadow_thickness(light_depth_tex, 0, light_block.lights[0], w.xyz / w.w)
                  : -1.0;
    if (t >= 0.0) c = viridis((t * frame.scale.x - debug.view.y) / (debug.view.z - debug.view.y));
  } else if (view == 8) {  // single scattering S(1), whatever the switch says
    if (scatters) {
      float depth = texelFetch(depth_tex, p, 0).r;
      vec4 w = frame.inv_view_proj * vec4(pixel_ndc(vec2(p) + 0.5, frame.viewport), depth, 1.0);
      SurfacePoint s;
      s.id = id;
      s.P = w.xyz / w.w;
      s.N = normalize(texelFetch(normal_tex, p, 0).xyz);
      s.thickness_mm = -1.0;  // S(1) alone: no transmission
      s.sky_blocked = vec3(0.0);
      s.V = frame.camera.w > 0.5 ? -frame.forward.xyz : normalize(frame.camera.xyz - s.P);
      s.albedo = texelFetch(albedo_tex, p, 0).rgb;
      c = display_encode(single_scattering_radiance(s));
    }
  } else if (view == 7) {  // uv stretch
    vec4 s = texelFetch(uv_stretch_tex, p, 0);
    if (s.z > 0.5) c = vec3(clamp((s.xy - debug.view.y) / (debug.view.z - debug.view.y), 0.0, 1.0), 0.0);
  }
  imageStore(display_img, p, vec4(c, 1.0));
}
