// Software skinning: the thesis's equations 1 and 2 over a range of a mesh.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "animation/skin_matrix.h"
#include "asset/character.h"

namespace crowdprof {

// Linear blend skinning of vertices [first_vertex, first_vertex + vertex_count)
// of `mesh`. Each vertex's matrix is the weighted sum of its (up to 4) joints'
// skinning matrices; positions go through the whole matrix (equation 1),
// normals through its 3x3 part and are re-normalised (equation 2; a normal that
// blends to zero length comes out zero). The mesh keeps weights sorted largest
// first, so the first zero weight ends a vertex's influences and the rest are
// skipped. Every vertex runs the same arithmetic whichever range it falls in, so
// any split of a mesh into ranges, on any threads, gives the same bits.
struct SkinningJob {
  std::span<const SkinMatrix> skinning_matrices;  // one per joint (pose.h)
  const SkinnedMesh* mesh = nullptr;
  size_t first_vertex = 0;
  size_t vertex_count = 0;
  // out_positions[i] and out_normals[i] receive vertex first_vertex + i; both
  // spans hold exactly vertex_count elements.
  std::span<glm::vec3> out_positions;
  std::span<glm::vec3> out_normals;

  // Mesh set and its arrays sized alike, range inside it, outputs sized to the
  // range, and every joint index of the range inside the palette (a scan of the
  // range's joint indices, far cheaper than skinning them).
  bool Validate() const;
  // False (and no output) when !Validate(). Allocates nothing.
  bool Run() const;
};

}  // namespace crowdprof
