#version 430 core
// A copy whose vertices were skinned on the CPU (master, culled, threaded, and
// hwskin's fallback): they arrive in the skin's model space every frame.
// With PACKED_POSITIONS (--vertex-format packed) positions arrive as 16-bit
// codes, normalised by GL to 0..1 across the character's box, and normals as
// 10:10:10:2 signed normalised (skinning/packed_vertex.h).

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 model;            // the copy's place in the crowd
uniform mat4 view_projection;  // the camera the crowd is culled with
#ifdef PACKED_POSITIONS
uniform vec3 position_min;     // the character's box, which the codes span
uniform vec3 position_extent;
#endif

out vec3 world_normal;

void main() {
#ifdef PACKED_POSITIONS
  vec3 model_position = position_min + position * position_extent;
#else
  vec3 model_position = position;
#endif
  world_normal = mat3(model) * normal;
  gl_Position = view_projection * (model * vec4(model_position, 1.0));
}
