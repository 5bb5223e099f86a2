// Thickness through an object along a light, from the light's shadow map (DESIGN.md §5:
// "it also gives thickness for transmission"): the distance from P back to the surface
// nearest the light on P's shadow-map texel, i.e. the path light travels inside the
// object before it reaches P (for a convex object; with several layers it is the distance
// to the first surface the light meets). Used by the thickness debug view and meant for
// transmission (issue 6). Not shared with C++.
#ifndef SSS_SHADERS_THICKNESS_GLSL
#define SSS_SHADERS_THICKNESS_GLSL

// Needs: shared/frame.h (GpuLight).

// shadow_depth: the shadow-map array read as depth (no comparison, nearest); layer: the
// light's layer. Returns the thickness in scene units, 0 where P is the surface nearest
// the light (the map's slope-scaled bias puts the stored depth just behind lit points),
// and -1 where P is outside the map or the light has no shadow map.
float shadow_thickness(sampler2DArray shadow_depth, int layer, GpuLight light, vec3 P) {
  if (light.shadow.y < 0.5) return -1.0;
  vec4 c = light.shadow_matrix * vec4(P, 1.0);
  vec3 s = c.xyz / c.w;
  vec2 uv = s.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || s.z > 1.0 || s.z < 0.0)
    return -1.0;
  // texelFetch of the nearest texel (what a nearest-filter textureLod reads): lavapipe
  // (Mesa 22.3) never finishes a fragment shader that calls textureLod on this array.
  ivec2 size = textureSize(shadow_depth, 0).xy;
  ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
  float d = texelFetch(shadow_depth, ivec3(texel, layer), 0).r;
  if (d >= s.z) return 0.0;
  // The nearest surface's point on P's shadow-map ray (exact for orthographic and
  // perspective shadow matrices).
  vec4 q = light.shadow_inverse * vec4(s.xy, d, 1.0);
  return length(P - q.xyz / q.w);
}

#endif
