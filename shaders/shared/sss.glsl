// What the screen-space SSS passes share: the surface key, the kernel's pixels per mm, and
// the follow-surface fallback (not shared with C++).
#ifndef SSS_SHADERS_SSS_GLSL
#define SSS_SHADERS_SSS_GLSL

// Needs: frame (FrameUniforms).

// The surface key that lighting.comp writes into the irradiance alpha (rgba32f) for the
// separable pass: view depth in mm plus material id x frame.options.z (the key stride, a
// power of two >= 2 x the scene's farthest depth + 1024 mm, make_frame_uniforms), or
// kBackgroundKey. Two texels of one material differ in key by their depth difference;
// texels of two materials (or the background) differ by more than any kernel width, so
// one bilinear fetch per tap carries the value and what follow-surface needs, and the key
// of a bilinear mix across a material boundary is as far from the centre's as the other
// material's. Float32: the key's rounding is 2^-24 x (id + 1) x stride (0.0002 mm for id
// 0 at a 2048 mm stride).
const float kBackgroundKey = -1.0e9;
float surface_key(int id, float z_mm) {
  return id < 0 ? kBackgroundKey : z_mm + float(id) * frame.options.z;
}
int key_material(float key) { return key < 0.0 ? -1 : int(key / frame.options.z); }
float key_depth(float key, int id) { return key - float(id) * frame.options.z; }

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
