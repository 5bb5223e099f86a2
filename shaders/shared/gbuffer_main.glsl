// The G-buffer fragment shader's body, shared by gbuffer.frag (the frame) and
// gbuffer_uv_stretch.frag (the uv-stretch debug view, which also writes the stretch).
// Not shared with C++.
#include "frame.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D textures[SSS_MAX_TEXTURES];
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 0) out vec4 out_normal_roughness;
layout(location = 1) out vec4 out_albedo_id;

void write_gbuffer() {
  vec3 n = normalize(in_normal);
  // Face the viewer whatever the winding: back faces are only seen on open meshes.
  vec3 to_eye = frame.camera.w > 0.5 ? -frame.forward.xyz : normalize(frame.camera.xyz - in_world);
  float facing = dot(n, to_eye) < 0.0 ? -1.0 : 1.0;
  n *= facing;
  int normal_slot = int(draw.textures.y);
  if (normal_slot >= 0 && dot(in_tangent.xyz, in_tangent.xyz) > 0.0) {
    // Tangent-space normal map (glTF: linear, +Y up in UV space), scaled in xy.
    vec3 t = normalize(in_tangent.xyz - n * dot(n, in_tangent.xyz));
    vec3 b = cross(n, t) * in_tangent.w * facing;
    vec3 m = texture(textures[normal_slot], in_uv).xyz * 2.0 - 1.0;
    m.xy *= draw.textures.z;
    n = normalize(t * m.x + b * m.y + n * max(m.z, 1e-4));
  }
  vec3 base = draw.base_color.rgb;
  int base_slot = int(draw.textures.x);
  if (base_slot >= 0) base *= texture(textures[base_slot], in_uv).rgb;  // sRGB view: linear
  out_normal_roughness = vec4(n, draw.material.z);
  out_albedo_id = vec4(clamp(base, 0.0, 1.0), (draw.material.x + 1.0) / 255.0);
}
