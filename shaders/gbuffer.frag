#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: normal + roughness (rgba16f) and albedo + material id (rgba8).
#include "shared/frame.h"

layout(set = 0, binding = 0) uniform Frame { FrameUniforms frame; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 0) out vec4 out_normal_roughness;
layout(location = 1) out vec4 out_albedo_id;

void main() {
  vec3 n = normalize(in_normal);
  // Face the viewer whatever the winding: back faces are only seen on open meshes.
  vec3 to_eye = frame.camera.w > 0.5 ? -frame.forward.xyz : normalize(frame.camera.xyz - in_world);
  if (dot(n, to_eye) < 0.0) n = -n;
  out_normal_roughness = vec4(n, draw.material.z);
  out_albedo_id = vec4(clamp(draw.base_color.rgb, 0.0, 1.0), (draw.material.x + 1.0) / 255.0);
}
