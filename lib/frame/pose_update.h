// The Animations stage's work on a frame's plan: each evaluation's pose
// sampled and built into its storage's skinning matrices, and (for characters
// skinned in Animations) its mesh skinned; in parallel on the bench's threads
// when the mode is parallel (thesis §4.3). Also the Rasterizer's skinning of
// mode master (skinning counted under Rasterizer, as the BGE's deformers were).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "asset/character.h"
#include "frame/bench_threads.h"
#include "frame/copy_store.h"
#include "base/modes.h"
#include "frame/prepared_character.h"
#include "frame/update_plan.h"
#include "measuring/animation_stages.h"
#include "measuring/category_clock.h"
#include "scene/crowd.h"
#include "skinning/output_buffer.h"

namespace crowdprof {

class Tracer;

// What a pose update reads and writes; everything outlives the updater.
struct PoseUpdateContext {
  std::span<const Character* const> characters;
  std::span<const PreparedCharacter> prepared;
  const Crowd* crowd = nullptr;
  CopyStore* store = nullptr;
  ModeSwitches mode;
  int threads = 1;  // worker threads when mode.parallel
  // When set, each parallel task is recorded as a span under process trace_pid.
  Tracer* tracer = nullptr;
  int trace_pid = 1;
  // Mesh LOD: per pose storage, the mesh level it is skinned at; empty: level 0.
  std::span<const uint8_t> mesh_level;
};

class PoseUpdater {
 public:
  // Allocates the per-thread scratch and takes the process's threads for
  // context.threads (bench_threads.h) when the mode is parallel.
  explicit PoseUpdater(const PoseUpdateContext& context);
  ~PoseUpdater();
  PoseUpdater(const PoseUpdater&) = delete;
  PoseUpdater& operator=(const PoseUpdater&) = delete;

  // Runs every job: its pose into its storage's palette and, when its
  // character is skinned in Animations, its skinned vertices. Returns the
  // string lookups made (mode master's per-frame paths; 0 with bindings).
  uint64_t update(std::span<const StateJob> jobs);
  // Skins each job's storage (characters skinned in Rasterizer, mode master).
  void skin(std::span<const StateJob> jobs);
  // The thread time update() spent in each stage since the last call, summed
  // over the threads (skin()'s Rasterizer work is not in it).
  AnimationStageTimes take_stage_times();

 private:
  // `skin`: also skin the job's storage when its character is skinned in
  // Animations (else the caller skins it, in parts: skin_range).
  void update_state(const StateJob& job, size_t slot, uint64_t* lookups, bool skin);
  // Samples action `action_index` of the job's character at `time` into
  // `pose` through `cursor` (resolving its paths into the slot's scratch with
  // string lookups).
  void sample_action(const StateJob& job, size_t slot, size_t action_index, float time, SamplingCursor& cursor,
                     LocalPose& pose, uint64_t* lookups);
  // Transitions: the pose a copy shows, `pose` or, fading, its blend with the
  // pose of the action it leaves (in the thread's scratch).
  // `since` moves on past the sampling and the blend it times.
  const LocalPose* fade(const StateJob& job, size_t slot, size_t action_index, const LocalPose& pose, uint64_t* lookups,
                        CategoryClock::Clock::time_point& since);
  // Layers (--anim-layer): the copy's own pose, or a fade's two (`own`), with
  // its character's layers laid over it, into the thread's scratch. Each
  // layer's action is sampled at layer_time of the own action's.
  const LocalPose* layered(const StateJob& job, size_t slot, size_t action_index, std::span<const BlendLayer> own,
                           uint64_t* lookups, CategoryClock::Clock::time_point& since);
  // Charges the time from `since` to now to `stage` on the calling thread (and
  // records it as a span when tracing); returns now.
  CategoryClock::Clock::time_point stage_done(AnimationStage stage, CategoryClock::Clock::time_point since);
  // How many parts update() skins each of this frame's states in: 1, or with
  // fewer states than threads (on a parallel mode skinning in Animations) two
  // parts a thread, so that one state keeps every thread busy.
  size_t skin_parts(size_t jobs) const;
  // The calling thread's index in the arena (0 without one): which per-thread
  // scratch (model_) a pose update uses.
  size_t worker_index() const;
  void skin_storage(size_t storage);
  // Part `part` of `parts` of a storage's mesh (whole kernel batches).
  void skin_range(size_t storage, size_t part, size_t parts);
  // While `posed` says the state's pose is not built yet, prefetches for
  // writing the skinned vertices from this part to the mesh's end.
  void prefetch_while(size_t storage, size_t part, size_t parts, const std::atomic<uint8_t>& posed) const;
  void skin_vertices(size_t storage, size_t first, size_t count);
  size_t level_of(size_t storage) const { return context_.mesh_level.empty() ? 0 : context_.mesh_level[storage]; }
  // Vertices of the storage's mesh level.
  size_t vertices_of(size_t storage) const {
    return context_.prepared[crowd_.kind[storage]].vertices_of(level_of(storage));
  }
  // The pose slot a job's leader is built in: its own, or its character's scratch.
  size_t slot_of(size_t copy) const;
  // `task` names the spans of its tasks in a trace.
  template <typename Body>
  void for_each_index(std::string_view task, size_t count, const Body& body);

  PoseUpdateContext context_;
  const Crowd& crowd_;
  CopyStore& store_;
  bool skins_in_animations_ = false;  // some character is skinned on the CPU in Animations
  // Model-space matrices, per thread x the most joints of a character: an
  // evaluation's intermediate (local-to-model, then the skinning matrices),
  // used at once. Per copy they were 4.4 KiB of the default character's 130
  // written and read back from memory every frame at 10,000 copies. Cache-line
  // aligned (a mat4 is one line), so that no two threads' regions share a line.
  std::vector<glm::mat4, CacheLineAllocator<glm::mat4>> model_;
  std::vector<LocalPose> blended_;  // transitions or layers: per thread, a copy's blended pose
  // Layers: per thread, kMaxAnimLayers sampled poses and additive deltas.
  std::vector<LocalPose> layer_poses_, layer_deltas_;
  // Per thread, nanoseconds in each stage: a line each, so that no two threads
  // write one.
  struct alignas(64) StageNanoseconds {
    std::array<int64_t, kAnimationStageCount> ns{};
  };
  std::vector<StageNanoseconds> stage_ns_;
  size_t model_joints_ = 0, model_threads_ = 1;
  // Per state when its mesh is skinned in parts: whether its pose is built yet.
  static constexpr uint8_t kNotPosed = 0, kPosing = 1, kPosed = 2;
  std::unique_ptr<std::atomic<uint8_t>[]> posed_;
  // The process's threads for this thread count, and their arena; both null
  // when the mode runs on the calling thread alone.
  std::shared_ptr<BenchThreads> threads_;
  tbb::task_arena* arena_ = nullptr;
};

}  // namespace crowdprof
