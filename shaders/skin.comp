#version 430 core
// Mode `compute` (issue 12): one pass skins a batch of copies into a vertex
// buffer that plain draws then read (crowd.vert), as UPBGE's and Unreal's GPU
// skin caches do. The same arithmetic as hwskin.vert, so the same picture.
// Work item (x, y): vertex x of the batch's copy y.

layout(local_size_x = 64) in;

struct RestVertex {
  vec4 position;  // w unused
  vec4 normal;    // w unused
  uvec4 joints;
  vec4 weights;
};
layout(std430, binding = 0) readonly buffer Rest { RestVertex rest[]; };
// Per copy of the batch, per joint: the 3 rows of its skinning matrix's 3x4 part.
layout(std430, binding = 1) readonly buffer Bones { vec4 bones[]; };
// Per copy of the batch, per vertex: skinned position then normal (w unused).
layout(std430, binding = 2) writeonly buffer Skinned { vec4 skinned[]; };

uniform uint vertex_count;
uniform uint joint_count;

void main() {
  uint v = gl_GlobalInvocationID.x, copy = gl_GlobalInvocationID.y;
  if (v >= vertex_count) return;
  RestVertex r = rest[v];
  uint base = 3u * joint_count * copy;
  vec4 row0 = vec4(0.0), row1 = vec4(0.0), row2 = vec4(0.0);
  for (int k = 0; k < 4; ++k) {
    uint j = base + 3u * r.joints[k];
    row0 += r.weights[k] * bones[j];
    row1 += r.weights[k] * bones[j + 1u];
    row2 += r.weights[k] * bones[j + 2u];
  }
  vec4 p = vec4(r.position.xyz, 1.0);
  vec3 n = vec3(dot(row0.xyz, r.normal.xyz), dot(row1.xyz, r.normal.xyz), dot(row2.xyz, r.normal.xyz));
  float length_n = length(n);
  n = length_n > 0.0 ? n / length_n : n;
  uint out_index = 2u * (copy * vertex_count + v);
  skinned[out_index] = vec4(dot(row0, p), dot(row1, p), dot(row2, p), 1.0);
  skinned[out_index + 1u] = vec4(n, 0.0);
}
