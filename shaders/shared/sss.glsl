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

// The surface's depth slope along `dir`, in mm of depth per mm of the camera plane: the
// one-sided difference to the neighbour of the centre's material with the smaller
// magnitude, so that a depth step on one side (an occluding edge) is not taken for slope;
// 0 without such a neighbour. dz_minus, dz_plus: z(p - dir) - z(p) and z(p + dir) - z(p)
// in mm, used where the flag says that neighbour is of the centre's material; ppm: the
// camera plane's pixels per mm at the centre.
float depth_slope(float dz_minus, bool minus_same, float dz_plus, bool plus_same, float ppm) {
  float forward = dz_plus * ppm, backward = -dz_minus * ppm;
  if (minus_same && plus_same) return abs(forward) < abs(backward) ? forward : backward;
  return plus_same ? forward : (minus_same ? backward : 0.0);
}

// depth_slope from the surface keys of the two neighbours (the separable pass's input and
// the irradiance target carry them in alpha): z is the centre's depth, id its material.
float key_depth_slope(float key_minus, float key_plus, int id, float z, float ppm) {
  return depth_slope(key_depth(key_minus, id) - z, key_material(key_minus) == id, key_depth(key_plus, id) - z,
                     key_material(key_plus) == id, ppm);
}

// Foreshortening: mm of surface per mm of the camera plane along a direction of depth
// slope s, sqrt(1 + s²). A kernel laid out in camera-plane mm reaches that much too far
// over a surface that turns away from the view (toward a silhouette) and mixes in light
// from beyond the profile's reach; dividing the pixels per mm by it keeps each tap at its
// surface distance (the stretch factors of Jimenez et al. 2009, "Screen-space perceptual
// rendering of human skin", with the measured slope instead of tuned constants).
float foreshortening(float slope) { return sqrt(1.0 + slope * slope); }

// A tap's value as the blur sees it: the centre value when the tap lies on another
// material or the background, and otherwise lerped toward the centre by how far its depth
// leaves the centre's tangent plane (z + slope x the tap's camera-plane offset), relative
// to the kernel width: follow surface (Jimenez 2015), measured from the plane so that a
// tilted surface keeps its whole kernel and only a depth step pulls the tap back.
vec3 follow_surface(vec3 tap, vec3 center, int tap_id, int id, float tap_z, float plane_z,
                    float width_mm) {
  if (tap_id != id) return center;
  return mix(tap, center, clamp(abs(tap_z - plane_z) / width_mm, 0.0, 1.0));
}

#endif
