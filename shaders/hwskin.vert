#version 430 core
// Skinning in the vertex shader (thesis 4.4): the rest mesh stays on the GPU,
// and each frame only the skinning matrices arrive, as the rows of their 3x4
// upper part (the fourth row of an affine matrix is always 0 0 0 1).
// MAX_BONES is defined by the renderer, from GL_MAX_VERTEX_UNIFORM_COMPONENTS.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uvec4 joints;
layout(location = 3) in vec4 weights;

uniform vec4 bones[3 * MAX_BONES];  // joint j: rows bones[3j], bones[3j+1], bones[3j+2]
uniform mat4 model;
uniform mat4 view_projection;

out vec3 world_normal;

void main() {
  // Equation 1: the vertex's matrix is the weighted sum of its joints' matrices
  // (unused influences have weight 0).
  vec4 row0 = vec4(0.0), row1 = vec4(0.0), row2 = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    int j = 3 * int(joints[k]);
    row0 += weights[k] * bones[j];
    row1 += weights[k] * bones[j + 1];
    row2 += weights[k] * bones[j + 2];
  }
  vec4 rest = vec4(position, 1.0);
  vec3 skinned = vec3(dot(row0, rest), dot(row1, rest), dot(row2, rest));
  // Equation 2: the normal by the matrix's 3x3 part, re-normalised (a normal
  // that blends to nothing stays zero, as on the CPU).
  vec3 n = vec3(dot(row0.xyz, normal), dot(row1.xyz, normal), dot(row2.xyz, normal));
  float length_n = length(n);
  n = length_n > 0.0 ? n / length_n : n;
  world_normal = mat3(model) * n;
  gl_Position = view_projection * (model * vec4(skinned, 1.0));
}
