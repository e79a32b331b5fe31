#version 430 core
// frustum gpu (issue 30): the GPU-driven crowd's cull pass. One invocation per
// copy tests its world box against the camera's six planes, as the CPU's
// Scenegraph does (scene/camera.cpp: intersects); a copy on screen takes the
// next slot of its character's indirect draw (an atomic add on the command's
// instance count) and writes its record there, as the CPU-culled path sends it
// (render/gpu_frame_buffers.h, GpuInstance: the instanced path's records): the
// copy (its placement is sent once, render/gpu_placements.h), which samples and
// where between them, from the simulated clock, as CrowdBench::update_logic and baked_position compute them
// on the CPU. With mesh LOD it also picks the
// copy's mesh level from the share of the screen's height its box spans, as
// scene/screen_size.cpp does, and appends it to that level's draw.
layout(local_size_x = 64) in;

struct CullCopy {
  vec4 box_min;  // xyz: the copy's world box
  vec4 box_max;
  uint kind;          // its character: the command it is drawn by
  uint first_row;     // its action's sample 0 in the baked table, in rows (3 x sample x joints)
  uint intervals;     // the action's samples - 1
  float phase;        // seconds into its action at time 0
  float start;        // the action's first key time
  float end;          // its last key time
  float duration;     // end - start; 0: always sample 0
  uint levels;        // mesh levels its character has, the full mesh counted (1: no mesh LOD)
};
layout(std430, binding = 0) readonly buffer Copies { CullCopy copies[]; };

// As baked.vert reads them (std430, 16 bytes: GpuInstance).
struct Instance {
  uint copy;
  uint first_row;  // GpuInstance.palette_base
  uint intervals;  // source[0]
  uint position;   // source[1]: a float's bits
};
layout(std430, binding = 1) writeonly buffer Instances { Instance instances[]; };

// glDrawElementsIndirect's command, one per character, or with mesh LOD one
// per character and level (kind x 4 + level); base_instance is where its
// records start in instances (the draw fetches its per-instance attributes from there).
struct Command {
  uint count;
  uint instance_count;
  uint first_index;
  int base_vertex;
  uint base_instance;
};
layout(std430, binding = 2) buffer Commands { Command commands[]; };

uniform vec4 planes[6];
uniform mat4 view_projection;
uniform float lod_thresholds[3];  // mesh LOD: level 1 below [0], 2 below [1], 3 below [2]
uniform uint commands_per_kind;   // 4 with mesh LOD, else 1
uniform double seconds;  // the frame's time, in double as the CPU's clock
uniform uint copy_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= copy_count) return;
  CullCopy c = copies[i];
  for (int p = 0; p < 6; ++p) {
    vec4 plane = planes[p];
    // The corner farthest along the plane's normal: if even it is outside, all are.
    vec3 corner = vec3(plane.x >= 0.0 ? c.box_max.x : c.box_min.x, plane.y >= 0.0 ? c.box_max.y : c.box_min.y,
                       plane.z >= 0.0 ? c.box_max.z : c.box_min.z);
    if (dot(plane.xyz, corner) + plane.w < 0.0) return;
  }
  float position = 0.0;
  if (c.duration > 0.0) {
    double local = mod(double(c.phase) + seconds, double(c.duration));
    float time = clamp(c.start + float(local), c.start, c.end);
    position = clamp((time - c.start) / c.duration * float(c.intervals), 0.0, float(c.intervals));
  }
  uint level = 0u;
  if (c.levels > 1u) {
    // screen_height_fraction: half the extent in NDC y of the eight corners; a
    // corner at or behind the eye makes the box fill the view.
    float low = 0.0, high = 0.0, fraction = -1.0;
    for (int corner = 0; corner < 8 && fraction < 0.0; ++corner) {
      vec4 p = vec4((corner & 1) != 0 ? c.box_max.x : c.box_min.x, (corner & 2) != 0 ? c.box_max.y : c.box_min.y,
                    (corner & 4) != 0 ? c.box_max.z : c.box_min.z, 1.0);
      vec4 clip = view_projection * p;
      if (clip.w <= 1e-6) fraction = 1.0;
      float y = clip.y / clip.w;
      low = corner == 0 ? y : min(low, y);
      high = corner == 0 ? y : max(high, y);
    }
    if (fraction < 0.0) fraction = min(1.0, 0.5 * (high - low));
    while (level + 1u < min(c.levels, 4u) && fraction < lod_thresholds[level]) ++level;
  }
  uint command = c.kind * commands_per_kind + level;
  uint slot = atomicAdd(commands[command].instance_count, 1u);
  instances[commands[command].base_instance + slot] =
      Instance(i, c.first_row, c.intervals, floatBitsToUint(position));
}
