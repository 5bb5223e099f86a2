// GLSL helpers of the screen passes (not shared with C++).
#ifndef SSS_SHADERS_COMMON_GLSL
#define SSS_SHADERS_COMMON_GLSL

const float kPi = 3.14159265358979;

// Material index from the G-buffer's albedo alpha; -1 for background.
int material_id(vec4 albedo_id) { return int(round(albedo_id.a * 255.0)) - 1; }

vec2 pixel_ndc(vec2 pixel_center, vec4 viewport) { return pixel_center * viewport.zw * 2.0 - 1.0; }

#endif
