// The order of a skinned mesh's vertices, chosen for the skinning loop.
#pragma once

#include <cstdint>
#include <vector>

#include "asset/character.h"

namespace crowdprof {

// Reorders the vertices of each of `mesh`'s primitives by the set of joints
// they weigh (its joint indices ascending, compared as words), keeping the
// file's order among vertices of one set, and renumbers `mesh.indices` to
// match: the same triangles, drawn alike. Returns, per new vertex, the index it
// had before. Why: skinning blends, per batch of 16 consecutive vertices, every
// joint any of them uses (skinning/skinning_plan.h); in the file's order the
// batches of Khronos' CesiumMan blend 5.06 joints, in this order 2.62 (the
// Fox 5.31 and 1.95, the bundled humanoid 3.06 and 2.64). Vertices of a
// primitive stay in its range; a mesh whose primitives' vertex ranges overlap,
// leave vertices out or fall outside the arrays is left as it is (identity).
std::vector<uint32_t> order_vertices_by_joints(SkinnedMesh& mesh);

// Orders the vertices of `character`'s mesh and of the file's own levels
// (MSFT_lod) as above. The loader keeps the file's order (what `info` and its
// messages describe); a bench orders its characters once, after loading them.
void order_vertices_for_skinning(Character& character);

}  // namespace crowdprof
