// Thickness through an object along a light, from the light's shadow map (DESIGN.md §5:
// "it also gives thickness for transmission"): the distance from P back to the surface
// nearest the light on P's shadow-map texel, i.e. the path light travels inside the
// object before it reaches P (for a convex object; with several layers it is the distance
// to the first surface the light meets). Used by transmission (shading.glsl) and the
// thickness debug view. Not shared with C++.
#ifndef SSS_SHADERS_THICKNESS_GLSL
#define SSS_SHADERS_THICKNESS_GLSL

// Needs: shared/frame.h (GpuLight).

// The map read here is the shadow pass's second rendering of each light, without the
// slope-scaled bias (targets.light_depth): where the light grazes a surface that bias is
// up to ~20 texels of depth (m = 7..15 on the facets of builtin:materials' spheres next
// to the terminator), and read as thickness it gave a dark band past the terminator and
// then bright dots where the facet changed (issue 20 part 3). Within one triangle the
// depth is affine in the texel position, so the lookup also moves the texel's depth from
// its centre to P's own position along the gradient that the neighbouring texels give:
// per axis the one-sided difference of smaller magnitude (the other side may lie on
// another triangle, or on the background at a silhouette).

// The depth gradient of the surface stored at `texel` along one axis (per texel), from
// the texels either side of it.
float light_depth_step(sampler2DArray light_depth, int layer, ivec2 texel, ivec2 axis,
                       ivec2 size, float d) {
  float before = texelFetch(light_depth, ivec3(clamp(texel - axis, ivec2(0), size - 1), layer), 0).r;
  float after = texelFetch(light_depth, ivec3(clamp(texel + axis, ivec2(0), size - 1), layer), 0).r;
  float back = d - before, ahead = after - d;
  return abs(back) < abs(ahead) ? back : ahead;
}

// light_depth: the unbiased depth array read as depth (no comparison, nearest); layer:
// the light's layer. Returns the thickness in scene units (0 where nothing lies between
// P and the light; on a lit surface that the light grazes, up to half the depth step of
// one texel), and -1 where P is outside the map or the light has no shadow map.
float shadow_thickness(sampler2DArray light_depth, int layer, GpuLight light, vec3 P) {
  if (light.shadow.y < 0.5) return -1.0;
  vec4 c = light.shadow_matrix * vec4(P, 1.0);
  vec3 s = c.xyz / c.w;
  vec2 uv = s.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || s.z > 1.0 || s.z < 0.0)
    return -1.0;
  // texelFetch of the nearest texel (what a nearest-filter textureLod reads): lavapipe
  // (Mesa 22.3) never finishes a fragment shader that calls textureLod on this array.
  ivec2 size = textureSize(light_depth, 0).xy;
  vec2 f = uv * vec2(size);
  ivec2 texel = clamp(ivec2(f), ivec2(0), size - 1);
  float d = texelFetch(light_depth, ivec3(texel, layer), 0).r;
  float z = 1.0;
  if (d < 1.0) {
    float gx = light_depth_step(light_depth, layer, texel, ivec2(1, 0), size, d);
    float gy = light_depth_step(light_depth, layer, texel, ivec2(0, 1), size, d);
    vec2 offset = f - (vec2(texel) + 0.5);
    z = d + gx * offset.x + gy * offset.y;
  }
  if (z >= s.z) {
    // No surface on P's texel, or one behind P (the plane overshot): P lies within a
    // texel of the outline seen from the light, or P is itself the nearest surface. The
    // light's path to P then lies between 0 and P's distance to the nearest surface on
    // the texels around it; the middle of that range, which is 0 for a lit surface
    // (nothing around it is nearer the light than the surface itself, within the
    // gradient) and on a grazing rim the half chord the map cannot resolve.
    float nearest = 1.0;
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        nearest = min(nearest, texelFetch(light_depth, ivec3(clamp(texel + ivec2(i, j), ivec2(0), size - 1), layer), 0).r);
    if (nearest >= s.z) return 0.0;
    z = 0.5 * (nearest + s.z);
  }
  // The nearest surface's point on P's shadow-map ray (exact for orthographic and
  // perspective shadow matrices).
  vec4 q = light.shadow_inverse * vec4(s.xy, max(z, 0.0), 1.0);
  return length(P - q.xyz / q.w);
}

#endif
