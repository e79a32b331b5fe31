// Each copy's placement (render/gpu_placements.h, GpuPlacement), sent when it
// changes, not every frame: an instance's record names its copy, and the
// vertex shader reads the placement here. Inserted ahead of the instanced
// and baked vertex shaders, after PLACEMENT_ROWS (a uniform page's rows) or
// PLACEMENTS_IN_STORAGE (frustum gpu: all copies in one storage block).

// Copy c's model matrix, rows 3c .. 3c+2 of its upper 3x4 (its fourth row is
// 0 0 0 1), c counted from its page's first. A uniform block: llvmpipe loads
// it cheaply where it gathers a storage block's element per vertex.
#ifdef PLACEMENTS_IN_STORAGE
layout(std430, binding = 1) readonly buffer Placements {
  vec4 placement_rows[];
};
#else
layout(std140, binding = 1) uniform Placements {
  vec4 placement_rows[PLACEMENT_ROWS];
};
#endif

mat4 placement_model(uint copy) {
  uint r = 3u * copy;
  return transpose(mat4(placement_rows[r], placement_rows[r + 1u], placement_rows[r + 2u], vec4(0.0, 0.0, 0.0, 1.0)));
}

// The copy's colour among colours[COLOURS], as the CPU's copy_colour(copy):
// a page holds whole cycles of them (GpuPlacements::copies_per_page).
uint placement_colour(uint copy) { return copy % uint(COLOURS); }
