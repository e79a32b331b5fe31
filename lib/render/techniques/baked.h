// Skinning from palettes sampled at load (mode baked, --skinning baked): each
// character's actions are baked into a table of palettes on the GPU once, and
// the copies are drawn through instanced's path (instanced.h): each frame sends
// one 16-byte record per copy on screen (the copy, which samples, how far
// between them; its placement was sent once, gpu_placements.h) and draws each
// character and mesh level with one instanced draw; the vertex shader blends
// the two samples. With transitions a fading copy sends 32 bytes, its record
// and the action it leaves (GpuFade), and the shader mixes the two. With
// frustum gpu the same records are made on the GPU (gpu_cull.h) and nothing
// per copy is sent (no transitions there: modes.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "render/character_meshes.h"
#include "render/gl_features.h"
#include "render/gpu_frame_buffers.h"
#include "render/gpu_placements.h"
#include "render/techniques/gpu_cull.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class BakedSkinning final : public Technique {
 public:
  explicit BakedSkinning(const GlFeatures& gl);
  ~BakedSkinning() override;

  // Uploads the baked tables of the characters the bench bakes and their rest
  // meshes; makes room for the records (throws GlUnavailable past the GPU's
  // free memory, as GpuFrameBuffers::reserve).
  void prepare(const FrameView& view, CharacterMeshes& meshes);
  // GPU storage held: tables, placements, instance records and the cull pass's buffers.
  uint64_t gpu_bytes() const { return gpu_bytes_; }

  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;
  // frustum gpu, after `view`'s frame has finished: the copies on screen per
  // character and mesh level (k x kMeshLevels + level), as the cull pass
  // counted them. False when the CPU culled.
  bool visible_counts(const FrameView& view, std::span<uint64_t> per_group) const;

 private:
  GlFeatures gl_;
  // Reading the placements from uniform pages (CPU-culled, or a crowd that
  // fits one page), or from one storage block (frustum gpu past one page:
  // its indirect draws cannot change pages).
  GlProgram program_, cull_program_;
  GLint joint_count_ = -1, cull_joint_count_ = -1;
  // With transitions: the program that draws the fading copies' two-slot
  // records (baked.vert's FADING), and how many this frame sent.
  GlProgram fading_program_;
  GLint fading_joint_count_ = -1;
  size_t fading_records_ = 0;
  bool cull_reads_storage(const FrameView& view) const;
  std::vector<GLuint> tables_;  // per character: every sample's 3x4 rows, 48 bytes a joint (0: not baked)
  GpuFrameBuffers buffers_;     // the records, without palettes
  GpuPlacements placements_;    // every copy's model matrix and colour, sent when they change
  uint64_t gpu_bytes_ = 0;
  // frustum gpu: writes the records and draws. One per bench prepared (a
  // compare's modes share the renderer, and each has its own switches: mesh
  // LOD or not), found by the view it was made for; none for a CPU-culled view.
  std::vector<std::pair<const FrameView*, std::unique_ptr<GpuCull>>> culls_;
  GpuCull* cull_for(const FrameView& view) const;
  std::vector<uint32_t> drawn_;  // scratch: per draw group (character, mesh level), copies on screen
};

}  // namespace crowdprof
