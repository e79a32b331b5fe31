// The buffers that GPU-skinned copies read in the buffer and instanced modes,
// inserted by the renderer ahead of the vertex shaders that use them
// (render/gpu_frame_buffers.h writes them, with the same std430 layout).

// Every palette drawn this frame, 3 rows (the 3x4 upper part) per joint:
// joint j of the palette that starts at row b is rows b+3j, b+3j+1, b+3j+2.
layout(std430, binding = 0) readonly buffer Palettes {
  vec4 bone_rows[];
};

// One record per instance of an instanced draw, a character kind's instances
// one after another. `source` is free for another skinning source (a baked
// animation's action and time, say); buffer palettes leave it zero. The same
// buffer is also bound as per-instance vertex attributes (buffer_skin.vert).
struct Instance {
  mat4 model;         // the copy's place in the crowd
  uint palette_base;  // its palette's first row in bone_rows
  uint colour;        // index into the frame's colours
  uint source0, source1;
};
layout(std430, binding = 1) readonly buffer Instances {
  Instance instances[];
};
