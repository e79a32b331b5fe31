#version 430 core
// Skinning in the vertex shader, as hwskin.vert, with the palettes in a shader
// storage buffer (shaders/instances.glsl, inserted ahead of this file) instead
// of a uniform array: no 128-bone limit. Without INSTANCED (mode buffer) a draw
// is one copy, named by uniforms; with INSTANCED (mode instanced) a draw is
// every copy of a character, and each instance's 16-byte record of
// instances.glsl arrives as per-instance attributes (fetched once per
// instance); its placement, sent once, is read from placements.glsl's buffer.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uvec4 joints;
layout(location = 3) in vec4 weights;

#ifdef INSTANCED
layout(location = 4) in uvec4 instance_data;  // copy, palette_base, source0, source1
uniform vec3 colours[COLOURS];
flat out vec3 instance_colour;
#else
uniform mat4 model;
uniform uint palette_base;
#endif
uniform mat4 view_projection;

out vec3 world_normal;

void main() {
#ifdef INSTANCED
  mat4 model = placement_model(instance_data.x);
  uint base = instance_data.y;
  instance_colour = colours[placement_colour(instance_data.x)];
#else
  uint base = palette_base;
#endif
  // Equation 1, as in hwskin.vert.
  vec4 row0 = vec4(0.0), row1 = vec4(0.0), row2 = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    uint j = base + 3u * joints[k];
    row0 += weights[k] * bone_rows[j];
    row1 += weights[k] * bone_rows[j + 1u];
    row2 += weights[k] * bone_rows[j + 2u];
  }
  vec4 rest = vec4(position, 1.0);
  vec3 skinned = vec3(dot(row0, rest), dot(row1, rest), dot(row2, rest));
  // Equation 2, as in hwskin.vert.
  vec3 n = vec3(dot(row0.xyz, normal), dot(row1.xyz, normal), dot(row2.xyz, normal));
  float length_n = length(n);
  n = length_n > 0.0 ? n / length_n : n;
  world_normal = mat3(model) * n;
  gl_Position = view_projection * (model * vec4(skinned, 1.0));
}
