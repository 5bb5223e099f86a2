// What both screen-space SSS passes share: material ids, view depth in mm, the kernel's
// pixels per mm, and the follow-surface fallback (not shared with C++).
#ifndef SSS_SHADERS_SSS_GLSL
#define SSS_SHADERS_SSS_GLSL

// Needs: frame (FrameUniforms), surface_tex (lighting.comp's surface image).

// x: distance from the camera plane in mm, y: material id (-1: background).
vec2 surface_at(ivec2 q) { return texelFetch(surface_tex, q, 0).xy; }

// Pixels per mm along `dir` at view depth z_mm. Orthographic: width / (2 xmag_mm);
// perspective: the focal length in pixels over the depth.
float pixels_per_mm(vec2 dir, float z_mm) {
  float focal_px = dir.x > 0.5 ? 0.5 * frame.viewport.x * frame.scale.y
                                : 0.5 * frame.viewport.y * frame.scale.z;
  return frame.camera.w > 0.5 ? focal_px / frame.scale.x : focal_px / z_mm;
}

// A tap's value as the blur sees it: the centre value when the tap lies on another
// material or the background, and otherwise lerped toward the centre by its depth
// difference relative to the kernel width (follow surface, Jimenez 2015).
vec3 follow_surface(vec3 tap, vec3 center, int tap_id, int id, float tap_z, float z,
                    float width_mm) {
  if (tap_id != id) return center;
  return mix(tap, center, clamp(abs(tap_z - z) / width_mm, 0.0, 1.0));
}

#endif
