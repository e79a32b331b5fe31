// The GPU-driven crowd's cull pass (frustum gpu, issue 30): a compute shader
// (shaders/cull.comp) tests every copy's world box against the camera and,
// for each copy on screen, picks its mesh level (mesh LOD; else level 0),
// appends its 16-byte record (the instanced path's GpuInstance, as baked's
// CPU-culled frames send it; the copy's placement is in gpu_placements.h's
// buffer) to its character's and level's range of the instance buffer
// and counts it in that range's indirect draw command. The
// CPU's work per frame is a few uniforms, one dispatch and one indirect draw
// per character and level: it does not grow with the crowd.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "measuring/counters.h"
#include "render/gl.h"
#include "render/gl_program.h"

namespace crowdprof {

struct FrameView;
class CharacterMeshes;
struct CharacterMesh;

class GpuCull {
 public:
  // Bytes a copy's box and clock take on the GPU (cull.comp's CullCopy).
  static constexpr uint64_t kBytesPerCopy = 64;

  // `first_record`: per character, or with mesh LOD per character and level
  // (k x kMeshLevels + level), where its records start in the instance buffer
  // (its character's copy count apart), and the end; `baked`: per character, whether it is drawn from a
  // baked table.
  GpuCull(const FrameView& view, const CharacterMeshes& meshes, std::span<const size_t> first_record,
          std::span<const uint8_t> baked);
  ~GpuCull();
  GpuCull(const GpuCull&) = delete;
  GpuCull& operator=(const GpuCull&) = delete;

  // Once a frame, before the passes: clears the instance counts and runs the
  // pass, writing the records into `instances` (GpuFrameBuffers::instance_buffer).
  void run(const FrameView& view, GLuint instances, Counters& counters);
  // Draws character k's copies on screen, level by level, with the program
  // bound (baked.vert), reading the records from `instances` as per-instance
  // attributes through the level's instanced VAO.
  void draw(size_t k, const CharacterMesh& mesh, GLuint instances, Counters& counters) const;
  // After the frame has finished: the copies on screen per character and mesh
  // level (k x kMeshLevels + level).
  void visible_counts(std::span<uint64_t> per_group) const;
  // GPU storage held: the copies' boxes and clocks, the commands.
  uint64_t gpu_bytes() const { return gpu_bytes_; }
  // Bytes of a record the pass writes, as the GL laid out cull.comp's
  // Instances (a GlError at construction unless sizeof(GpuInstance)).
  uint64_t record_bytes() const { return record_bytes_; }

 private:
  struct Command {
    uint32_t count, instance_count, first_index;
    int32_t base_vertex;
    uint32_t base_instance;
  };
  static_assert(sizeof(Command) == 20);

  GlProgram program_;
  // Reads record_bytes_ from the program; throws GlError unless the draws' record size.
  void check_record_stride();

  GLint planes_ = -1, view_projection_ = -1, thresholds_ = -1, per_kind_uniform_ = -1, seconds_ = -1, copy_count_ = -1;
  uint64_t record_bytes_ = 0;
  GLuint copies_ = 0, commands_ = 0;
  std::vector<Command> cleared_;  // the commands with no instance: each frame starts from them
  std::vector<uint8_t> drawn_;    // per character and level: drawn (a baked character's level it has)
  size_t copy_count_value_ = 0;
  size_t per_kind_ = 1;  // commands per character: kMeshLevels with mesh LOD, else 1
  uint64_t gpu_bytes_ = 0;
};

}  // namespace crowdprof
