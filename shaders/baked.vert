#version 430 core
// Mode `baked` (issue 12): every action was sampled at load into a table of
// skinning matrices (rows of their 3x4 parts). Copies are drawn through the
// instanced path that mode instanced uses (issue 30): an instanced draw covers
// a character's visible copies at one mesh level, and each instance's 16-byte
// record (render/gpu_frame_buffers.h, GpuInstance) arrives as per-instance
// attributes: its copy, whose placement (model matrix) was sent once
// (shaders/placements.glsl, inserted ahead of this file), and, where instanced
// has its palette, which samples to read and where between them. The matrices are interpolated
// linearly between the two samples around the copy's time, then the vertex is
// skinned as in hwskin.vert. With transitions (issue 53) a fading copy's
// record has a second slot, the action it leaves (FADING), and the two
// actions' matrices are mixed by the fade's weight.

layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in uvec4 joints;
layout(location = 3) in vec4 weights;
// x: the copy; y: the first row of its action in the table (3 x its sample 0
// x joint_count); z: the action's samples - 1; w: the copy's position among
// them (sample index and fraction), a float's bits.
layout(location = 4) in uvec4 instance_data;
#ifdef FADING
// A fading copy's second slot (GpuFade): the action it leaves, as y, z, w
// above (its first row, samples - 1, position), and that action's weight (a
// float's bits).
layout(location = 5) in uvec4 fade_data;
#endif

// Sample s, joint j: rows baked[3 (s joint_count + j)] .. + 2.
layout(std430, binding = 0) readonly buffer Baked { vec4 baked[]; };

uniform uint joint_count;
uniform vec3 colours[COLOURS];
uniform mat4 view_projection;

out vec3 world_normal;
flat out vec3 instance_colour;

// Adds `share` of the vertex's skinning rows at position `at` among an
// action's samples (from row `first_row`, `intervals` of them).
void add_baked_rows(uint first_row, uint intervals, float at, float share, inout vec4 row0, inout vec4 row1,
                    inout vec4 row2) {
  uint first = min(uint(at), intervals - 1u);
  float w = min(at - float(first), 1.0);
  uint a = first_row + 3u * first * joint_count, b = a + 3u * joint_count;
  for (int k = 0; k < 4; ++k) {
    uint j = 3u * joints[k];
    // (1 - w) A + w B, as BakedPaletteJob computes it on the CPU.
    float s = share * weights[k];
    row0 += s * (baked[a + j] * (1.0 - w) + baked[b + j] * w);
    row1 += s * (baked[a + j + 1u] * (1.0 - w) + baked[b + j + 1u] * w);
    row2 += s * (baked[a + j + 2u] * (1.0 - w) + baked[b + j + 2u] * w);
  }
}

void main() {
  vec4 row0 = vec4(0.0), row1 = vec4(0.0), row2 = vec4(0.0);
#ifdef FADING
  // A fade mixes the two actions' matrices, not the two skinned vertices:
  // skinning is linear in the matrices, so the positions are the same, and
  // this skins and normalises once; BakedFadeJob computes the same on the CPU.
  float left = uintBitsToFloat(fade_data.w);
  add_baked_rows(instance_data.y, instance_data.z, uintBitsToFloat(instance_data.w), 1.0 - left, row0, row1, row2);
  add_baked_rows(fade_data.x, fade_data.y, uintBitsToFloat(fade_data.z), left, row0, row1, row2);
#else
  add_baked_rows(instance_data.y, instance_data.z, uintBitsToFloat(instance_data.w), 1.0, row0, row1, row2);
#endif
  vec4 rest = vec4(position, 1.0);
  vec3 skinned = vec3(dot(row0, rest), dot(row1, rest), dot(row2, rest));
  vec3 n = vec3(dot(row0.xyz, normal), dot(row1.xyz, normal), dot(row2.xyz, normal));
  float length_n = length(n);
  n = length_n > 0.0 ? n / length_n : n;
  mat4 model = placement_model(instance_data.x);
  world_normal = mat3(model) * n;
  instance_colour = colours[placement_colour(instance_data.x)];
  gl_Position = view_projection * (model * vec4(skinned, 1.0));
}
