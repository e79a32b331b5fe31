// The buffers that GPU-skinned copies read in the buffer and instanced modes,
// inserted by the renderer ahead of the vertex shaders that use them
// (render/gpu_frame_buffers.h writes them, with the same std430 layout).

// Every palette drawn this frame, 3 rows (the 3x4 upper part) per joint:
// joint j of the palette that starts at row b is rows b+3j, b+3j+1, b+3j+2.
layout(std430, binding = 0) readonly buffer Palettes {
  vec4 bone_rows[];
};

// The instanced draws' records (render/gpu_frame_buffers.h, GpuInstance: the
// copy, whose placement shaders/placements.glsl holds, then palette_base and
// two words of the skinning source's: unused here, baked.vert's interval
// count and position) reach the vertex shader as per-instance attributes, not
// as a storage block: fetched once per instance, not gathered per vertex.
