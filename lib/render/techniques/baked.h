// Skinning from palettes sampled at load (mode baked, --skinning baked): each
// character's actions are baked into a table of palettes on the GPU once, every
// copy's placement goes up once, and each frame sends one 16-byte record per
// copy on screen (which sample, how far to the next) and draws each character
// with one instanced draw; the vertex shader blends the two samples. With
// frustum gpu the records are made on the GPU (gpu_cull.h) and nothing per copy
// is sent.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "render/character_meshes.h"
#include "render/techniques/gpu_cull.h"
#include "render/techniques/technique.h"

namespace crowdprof {

class BakedSkinning final : public Technique {
 public:
  BakedSkinning();
  ~BakedSkinning() override;

  // Uploads the baked tables of the characters the bench bakes, their rest
  // meshes, and every copy's placement (copies stand still).
  void prepare(const FrameView& view, CharacterMeshes& meshes);
  // GPU storage held: tables, placements and instance records.
  uint64_t gpu_bytes() const { return gpu_bytes_; }

  void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) override;
  void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) override;
  // frustum gpu, after `view`'s frame has finished: the copies on screen per
  // character and mesh level (k x kMeshLevels + level), as the cull pass
  // counted them. False when the CPU culled.
  bool visible_counts(const FrameView& view, std::span<uint64_t> per_group) const;

 private:
  struct InstanceRecord {
    uint32_t copy, first_sample, intervals;
    float position;
  };
  static_assert(sizeof(InstanceRecord) == 16);

  GlProgram program_;
  GLint joint_count_ = -1, first_instance_ = -1;
  std::vector<GLuint> tables_;  // per character: every sample's 3x4 rows, 48 bytes a joint (0: not baked)
  GLuint placements_ = 0, instances_ = 0;
  size_t instance_capacity_ = 0;
  uint64_t gpu_bytes_ = 0;
  // frustum gpu: writes the records and draws. One per bench prepared (a
  // compare's modes share the renderer, and each has its own switches: mesh
  // LOD or not), found by the view it was made for; none for a CPU-culled view.
  std::vector<std::pair<const FrameView*, std::unique_ptr<GpuCull>>> culls_;
  GpuCull* cull_for(const FrameView& view) const;
  std::vector<InstanceRecord> records_;  // scratch: this frame's, grouped by character
  std::vector<size_t> first_;            // scratch: each draw group's (character, mesh level) first record, then the end
  std::vector<size_t> next_;             // scratch: each draw group's next record to place
};

}  // namespace crowdprof
