// Texture path, atlas G-buffer (d'Eon & Luebke 2007, GPU Gems 3 ch. 14): per atlas texel,
// the surface point it holds (world position, UV island, shading normal, base colour)
// and the stretch map: mm of surface per texel along u and along v. The target's x is u
// and y is v, so the screen derivatives of the world position ARE dP/du and dP/dv per
// texel (exact: a triangle is affine in UV). The normal is the mesh's own (no viewer to
// face). texture_lighting.comp shades these texels; the lighting is not done here because
// lavapipe (Mesa 22.3) crashes or hangs compiling fragment shaders that sample the shadow
// maps after this pass's descriptor set was bound, and compute shading is what the screen
// path already runs. With an environment (texture_irradiance_sky.frag) a fifth target
// holds the sky's blocked irradiance (surface.glsl, sky_blocked).
#include "surface.glsl"

layout(location = 4) flat in float in_island;
layout(location = 0) out vec4 out_position;  // world xyz, w the UV island + 1 (0: empty)
layout(location = 1) out vec4 out_normal;    // xyz, w inward thickness (mm)
layout(location = 2) out vec4 out_albedo;    // rgb base colour
layout(location = 3) out vec4 out_stretch;   // x mm per texel along u, y along v
#ifdef SSS_SKY_OCCLUSION
layout(location = 4) out vec4 out_sky_blocked;  // rgb E_blocked (surface.glsl), a 0
#endif

void main() {
  out_position = vec4(in_world, in_island + 1.0);
  out_normal = vec4(shading_normal(1.0), thickness_mm());
  out_albedo = vec4(base_colour(), 1.0);
  out_stretch = vec4(length(dFdx(in_world)) * frame.scale.x, length(dFdy(in_world)) * frame.scale.x,
                     0.0, 1.0);
#ifdef SSS_SKY_OCCLUSION
  out_sky_blocked = vec4(sky_blocked(), 0.0);
#endif
}
