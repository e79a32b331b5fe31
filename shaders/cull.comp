#version 430 core
// frustum gpu (issue 30): the GPU-driven crowd's cull pass. One invocation per
// copy tests its world box against the camera's six planes, as the CPU's
// Scenegraph does (scene/camera.cpp: intersects); a copy on screen takes the
// next slot of its character's indirect draw (an atomic add on the command's
// instance count) and writes its baked record there: which samples and where
// between them, from the simulated clock, as CrowdBench::update_logic and
// baked_position compute them on the CPU.
layout(local_size_x = 64) in;

struct CullCopy {
  vec4 box_min;  // xyz: the copy's world box
  vec4 box_max;
  uint kind;          // its character: the command it is drawn by
  uint first_sample;  // its action's sample 0 in the baked table
  uint intervals;     // the action's samples - 1
  float phase;        // seconds into its action at time 0
  float start;        // the action's first key time
  float end;          // its last key time
  float duration;     // end - start; 0: always sample 0
  uint pad;
};
layout(std430, binding = 0) readonly buffer Copies { CullCopy copies[]; };

// As baked.vert reads them.
struct Instance {
  uint copy;
  uint first_sample;
  uint intervals;
  float position;
};
layout(std430, binding = 1) writeonly buffer Instances { Instance instances[]; };

// glDrawElementsIndirect's command, one per character; base_instance is where
// its records start in instances (baked.vert is told it as first_instance).
struct Command {
  uint count;
  uint instance_count;
  uint first_index;
  int base_vertex;
  uint base_instance;
};
layout(std430, binding = 2) buffer Commands { Command commands[]; };

uniform vec4 planes[6];
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
  uint slot = atomicAdd(commands[c.kind].instance_count, 1u);
  instances[commands[c.kind].base_instance + slot] = Instance(i, c.first_sample, c.intervals, position);
}
