// The form skinning matrices take between the pose update and skinning.
#pragma once

#include <glm/glm.hpp>

namespace crowdprof {

// model x inverse bind of one joint, as a column-major glm::mat4. A 3x4 form
// (three rows) would be 48 bytes instead of 64, but the palette (69 joints:
// 4.4 KiB) sits in L1 either way, and software skinning blends and transforms
// whole columns as two 8-float halves with fewer instructions than rows that
// need dot products (docs/experiments.md). A GPU upload may still pack rows;
// that is the renderer's choice.
using SkinMatrix = glm::mat4;

}  // namespace crowdprof
