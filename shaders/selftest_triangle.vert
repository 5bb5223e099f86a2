// Self-test of the graphics pipeline builder (tests/vk): positions and colours from a
// vertex buffer, passed through.
#version 460

layout(location = 0) in vec3 position;
layout(location = 1) in vec4 color;

layout(location = 0) out vec4 v_color;

void main() {
  v_color = color;
  gl_Position = vec4(position, 1.0);
}
