#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer for the uv-stretch debug view (its own pipeline, so that the frame's G-buffer
// pays nothing): the G-buffer of gbuffer.frag plus, in a third target, mm of surface per
// unit of u and v from the screen derivatives of the world position and the UVs
// (x: |dP/du| mm, y: |dP/dv| mm, z: 1 where the UVs span the surface, 0 where they do not,
// e.g. a mesh without UVs, whose UVs are all 0).
#include "shared/gbuffer_main.glsl"

layout(location = 2) out vec4 out_uv_stretch;

void main() {
  write_gbuffer();
  vec3 px = dFdx(in_world), py = dFdy(in_world);
  vec2 ux = dFdx(in_uv), uy = dFdy(in_uv);
  // (du, dv) = J (dx, dy) with J = [ux.x uy.x; ux.y uy.y]; dP/du and dP/dv through J^-1.
  float det = ux.x * uy.y - uy.x * ux.y;
  float span = max(max(abs(ux.x), abs(ux.y)), max(abs(uy.x), abs(uy.y)));
  if (abs(det) <= 1e-12 * max(span * span, 1e-30) || span == 0.0) {
    out_uv_stretch = vec4(0.0);
    return;
  }
  vec3 dp_du = (px * uy.y - py * ux.y) / det;
  vec3 dp_dv = (py * ux.x - px * uy.x) / det;
  out_uv_stretch = vec4(length(dp_du) * frame.scale.x, length(dp_dv) * frame.scale.x, 1.0, 0.0);
}
