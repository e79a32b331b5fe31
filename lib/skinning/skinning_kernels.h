// The SIMD kernels behind SkinningJob, compiled once per target (Highway) and
// picked at run time for the CPU (simd_target.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "skinning/skinning_plan.h"

namespace crowdprof {

struct SkinKernelArgs {
  const SkinningPlan* plan = nullptr;
  const float* palette = nullptr;  // 16 floats (a column-major mat4) per joint
  size_t first_vertex = 0, end_vertex = 0;
  float* positions = nullptr;  // x, y, z of vertex first_vertex onwards
  float* normals = nullptr;
  // Single-influence batches keep their rotated normals (every such joint rigid).
  bool keep_single_normals = false;
  // Float format only: non-temporal stores for the batches whose positions and
  // normals start on a 64-byte boundary, then a store fence. Output bound for
  // memory rather than cache is written without first being read in.
  bool stream = false;
  // The packed format (packed_vertex.h) instead of positions and normals: 3
  // position codes and one normal word per vertex from first_vertex onwards.
  uint16_t* packed_positions = nullptr;
  uint32_t* packed_normals = nullptr;
  float quantisation_min[3] = {0, 0, 0};
  float quantisation_scale[3] = {0, 0, 0};
};

// Skins the vertices [first_vertex, end_vertex) (checked by SkinningJob).
void run_skinning_kernel(const SkinKernelArgs& args);

// Whether the kernels run_skinning_kernel calls now fuse multiplies and adds
// (AVX2 and up) or round each (SSE4 and below): the two give different last
// bits, so a digest is the same only between targets that answer alike.
bool skinning_fuses_multiply_add();

}  // namespace crowdprof
