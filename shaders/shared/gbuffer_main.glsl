// The G-buffer fragment shader's body, shared by gbuffer.frag (the frame) and
// gbuffer_uv_stretch.frag (the uv-stretch debug view, which also writes the stretch) and
// gbuffer_sky.frag (with an environment: also the sky's blocked irradiance).
// Not shared with C++.
#include "surface.glsl"

layout(location = 0) out vec4 out_normal_thickness;  // xyz normal, w inward thickness (mm)
layout(location = 1) out vec4 out_albedo_id;
#ifdef SSS_SKY_OCCLUSION
layout(location = 2) out vec4 out_sky_blocked;  // rgb E_blocked (surface.glsl), a 0
#endif

void write_gbuffer() {
  // Face the viewer whatever the winding: back faces are only seen on open meshes.
  vec3 to_eye = frame.camera.w > 0.5 ? -frame.forward.xyz : normalize(frame.camera.xyz - in_world);
  float facing = dot(normalize(in_normal), to_eye) < 0.0 ? -1.0 : 1.0;
  out_normal_thickness = vec4(shading_normal(facing), thickness_mm());
  out_albedo_id = vec4(base_colour(), (draw.material.x + 1.0) / 255.0);
#ifdef SSS_SKY_OCCLUSION
  out_sky_blocked = vec4(sky_blocked(), 0.0);
#endif
}
