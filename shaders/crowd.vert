#version 430 core
// A copy whose vertices were skinned on the CPU (master, culled, threaded, and
// hwskin's fallback): they arrive in the skin's model space every frame.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 model;            // the copy's place in the crowd
uniform mat4 view_projection;  // the camera the crowd is culled with

out vec3 world_normal;

void main() {
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * (model * vec4(position, 1.0));
}
