#version 430 core
// Mode `baked` (issue 12): every action was sampled at load into a table of
// skinning matrices (rows of their 3x4 parts). An instanced draw covers every
// visible copy of a character; each instance carries only which samples to
// read and where between them, and its copy's placement, uploaded once
// (copies stand still). The matrices are interpolated linearly between the two
// samples around the copy's time, then the vertex is skinned as in hwskin.vert.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uvec4 joints;
layout(location = 3) in vec4 weights;

// Sample s, joint j: rows baked[3 (s joint_count + j)] .. + 2.
layout(std430, binding = 0) readonly buffer Baked { vec4 baked[]; };
struct Placement {
  mat4 model;
  vec4 colour;
};
layout(std430, binding = 1) readonly buffer Placements { Placement placements[]; };
struct Instance {
  uint copy;          // index into placements
  uint first_sample;  // the action's sample 0 in the table
  uint intervals;     // the action's samples - 1
  float position;     // where in them: sample index and fraction
};
layout(std430, binding = 2) readonly buffer Instances { Instance instances[]; };

uniform uint joint_count;
uniform uint first_instance;  // this draw's first entry in instances
uniform mat4 view_projection;

out vec3 world_normal;
flat out vec3 instance_colour;

void main() {
  Instance instance = instances[first_instance + uint(gl_InstanceID)];
  uint first = min(uint(instance.position), instance.intervals - 1u);
  float w = min(instance.position - float(first), 1.0);
  uint a = 3u * (instance.first_sample + first) * joint_count, b = a + 3u * joint_count;
  vec4 row0 = vec4(0.0), row1 = vec4(0.0), row2 = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    uint j = 3u * joints[k];
    // (1 - w) A + w B, as BakedPaletteJob computes it on the CPU.
    row0 += weights[k] * (baked[a + j] * (1.0 - w) + baked[b + j] * w);
    row1 += weights[k] * (baked[a + j + 1u] * (1.0 - w) + baked[b + j + 1u] * w);
    row2 += weights[k] * (baked[a + j + 2u] * (1.0 - w) + baked[b + j + 2u] * w);
  }
  vec4 rest = vec4(position, 1.0);
  vec3 skinned = vec3(dot(row0, rest), dot(row1, rest), dot(row2, rest));
  vec3 n = vec3(dot(row0.xyz, normal), dot(row1.xyz, normal), dot(row2.xyz, normal));
  float length_n = length(n);
  n = length_n > 0.0 ? n / length_n : n;
  Placement placement = placements[instance.copy];
  world_normal = mat3(placement.model) * n;
  instance_colour = placement.colour.rgb;
  gl_Position = view_projection * (placement.model * vec4(skinned, 1.0));
}
