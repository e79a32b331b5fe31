// The frame loop: a crowd of copies of one or more characters, stepped one
// frame at a time through the BGE's stages in the BGE's order, each charged to
// its profile category by one clock.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "animation/bake.h"
#include "animation/binding.h"
#include "animation/local_pose.h"
#include "animation/pose_sharing.h"
#include "animation/update_rates.h"
#include "animation/sampling.h"
#include "animation/skin_matrix.h"
#include "asset/character.h"
#include "frame/bench_threads.h"
#include "frame/frame_renderer.h"
#include "frame/modes.h"
#include "profile/category_clock.h"
#include "profile/counters.h"
#include "scene/camera.h"
#include "scene/crowd.h"
#include "skinning/output_buffer.h"
#include "skinning/packed_vertex.h"
#include "skinning/skinning_plan.h"

namespace crowdprof {

class Tracer;

struct BenchConfig {
  CrowdOptions crowd;  // groups index the characters the bench is made with
  std::string mode_name = "threaded";
  ModeSwitches mode;
  int threads = 1;  // worker threads when mode.parallel
  double fps = 60.0;  // the simulated clock: frame k shows time k / fps
  // Mode `baked`: samples per second each action is baked at (--bake-rate).
  float bake_rate_hz = kDefaultBakeRateHz;
  std::string camera = "default";
  Lens lens;  // Blender's: 35 mm on a 32 mm sensor fitted to the larger side
  float aspect = 16.0f / 9.0f;
  std::string resolution = "1600x900";  // WxH of the frame the aspect is from, as reports show it
  // Draws each frame (Rasterizer) and waits for it (GPU Latency); null: no
  // backend. Needed for skinning on the GPU. Not owned; outlives the bench.
  FrameRenderer* renderer = nullptr;
  // When set, each stage of each frame and each parallel task is recorded as a
  // span under process `trace_pid` (--trace); null records nothing, at no cost.
  Tracer* tracer = nullptr;
  int trace_pid = 1;
  // For reports only: each character's file as the user named it, and the
  // scene file the run came from (empty for a character given directly).
  std::vector<std::string> files;
  std::string scene_file, scene_hash;
  bool actions_from_scene = false;  // each group's actions as its scene file says
  // For tests of the animation budget: when not empty, the budget's controller
  // reads frame f's Animations time as replay_animations_ms[(f - 1) % size]
  // instead of the clock's, so its choices (and the digest) are reproducible.
  std::vector<double> replay_animations_ms;
};

// How faithfully a run's copies followed their exact times (issue 13): the
// largest distance between a vertex as drawn and where the copy's exact time
// would put it, over every copy on screen in the last frame.
struct AnimationFidelity {
  double max_deviation = 0;        // model units (the character's own space)
  double deviation_fraction = 0;   // of that copy's character's height
  size_t copies_checked = 0;       // copies on screen that were compared
  size_t copies_deviating = 0;     // of those, copies whose time drawn was not their exact time
};

// How the run scheduled pose updates (issue 13), over every frame run.
struct UpdateSchedule {
  uint64_t longest_gap = 0;  // most frames between two updates of one copy (0: none updated twice)
  // Copies posed in the last frame, by period: copies[s] are updated every 2^s frames.
  std::array<uint64_t, kRateCount> copies_by_rate{};
  uint64_t demotions = 0;  // the budget's doublings in the last frame
};

// Empty when a bench of this config can run, else why not: switches that
// conflict, skinning on the GPU without a renderer, a bake rate that is not a
// positive number.
std::string why_cannot_run(const BenchConfig& config);

// Bytes a crowd would allocate, to refuse a scene before trying.
uint64_t estimate_bench_bytes(const Character& character, size_t copies, const ModeSwitches& mode);
uint64_t estimate_bench_bytes(std::span<const Character* const> characters, const CrowdOptions& crowd,
                              const ModeSwitches& mode);

class CrowdBench {
 public:
  // Allocates everything the frames need; steps allocate nothing. Throws
  // UsageError for switches that cannot run together. The characters outlive
  // the bench; config.crowd's groups index them.
  CrowdBench(std::span<const Character* const> characters, const BenchConfig& config);
  CrowdBench(const Character& character, const BenchConfig& config);
  ~CrowdBench();
  CrowdBench(const CrowdBench&) = delete;
  CrowdBench& operator=(const CrowdBench&) = delete;

  // Runs one frame and returns where its time went and the work it did. Its
  // GPU time is not known yet: gpu_times() gives earlier frames' as their
  // timer queries finish.
  FrameRecord step();

  // The GPU times (frame numbers as frames_run() counted them) that the last
  // step() read, or that collect_gpu_times() waited for.
  std::span<const GpuTime> gpu_times() const { return std::span(gpu_times_).first(gpu_time_count_); }
  // After the last frame: waits for the GPU times still in flight.
  void collect_gpu_times();
  // Empty when the renderer times frames on the GPU, else why not ("no GL backend").
  std::string gpu_timing_missing() const;
  // The GPU timer's resolution in ms (FrameRenderer); 0 without one.
  double gpu_timer_resolution_ms() const;

  // Forgets the time since the last frame: the next frame is not charged (as
  // Outside) for what ran in between, e.g. the other modes of a compare.
  void restart_clock() { clock_ = CategoryClock{}; }

  // A hash (hex FNV-1a 64) of the last frame's skinning matrices and skinned
  // vertices of the copies inside the frustum: equal across modes and thread
  // counts when they compute the same thing. With packed vertices, the packed
  // bytes are hashed (what the GPU reads) instead of the floats.
  std::string digest() const;

  const Crowd& crowd() const { return crowd_; }
  const Camera& camera() const { return camera_; }
  // The first character: the only one unless the crowd is mixed.
  const Character& character() const { return *characters_.front(); }
  std::span<const Character* const> characters() const { return characters_; }
  const Character& character_of(size_t copy) const { return *characters_[crowd_.kind[copy]]; }
  // The last frame's counters of each character's copies (indexed as
  // characters()); draw calls and bytes are only counted in all.
  std::span<const Counters> character_counters() const { return character_counters_; }
  const BenchConfig& config() const { return config_; }
  // The pose storage copy `copy` draws: its own, or with animation sharing
  // that of the state it shows (copies in one state draw one storage).
  size_t storage_of(size_t copy) const { return config_.mode.share_poses ? sharing_.shown(copy) : copy; }
  // Share of the screen's height the copy's box spans (screen_size.h).
  float screen_fraction(size_t copy) const { return screen_fraction_[copy]; }
  // Exact times against what the last frame drew; skins every copy on screen
  // twice, so it is for the end of a run (allocates, takes time).
  AnimationFidelity measure_fidelity() const;
  const UpdateSchedule& schedule() const { return schedule_; }
  size_t frames_run() const { return frame_; }
  bool visible(size_t copy) const { return visible_[copy] != 0; }
  // True when the renderer skins this character (mode hwskin and the character
  // within its bone limit, or compute, or baked): its copies' skinned_positions()
  // stay in the rest pose.
  bool gpu_skinned_kind(size_t kind) const { return skins_on_gpu(kinds_[kind].site); }
  // Where this character's copies are skinned: the mode's site, or the CPU for
  // a character over hwskin's bone limit.
  SkinningSite site_of_kind(size_t kind) const { return kinds_[kind].site; }
  bool gpu_skinned_copy(size_t copy) const { return gpu_skinned_kind(crowd_.kind[copy]); }
  // Every character skinned by the renderer.
  bool gpu_skinned() const;
  std::span<const SkinMatrix> skinning_matrices(size_t copy) const;
  // Float vertices skinned on the CPU are written with streaming stores: the
  // frame's output is larger than the caches (skinning/output_stores.h). Each
  // copy's skinned_positions() and skinned_normals() start on a cache line.
  bool streams_output() const { return stream_output_; }
  std::span<const glm::vec3> skinned_positions(size_t copy) const;
  std::span<const glm::vec3> skinned_normals(size_t copy) const;
  // This frame's time of a copy on its action's clock (from the Logic stage).
  float action_time(size_t copy) const { return times_[copy]; }

  // Mode baked: each character's actions baked at load (a character without
  // actions: its rest palette twice, one interval), null in other modes.
  const BakedCharacter* baked(size_t kind) const { return kinds_[kind].baked.joints ? &kinds_[kind].baked : nullptr; }
  // Where a copy reads its baked samples this frame: the action's first sample,
  // its interval count and the position among them (baked_position).
  struct BakedInstance {
    uint32_t first_sample = 0, intervals = 1;
    float position = 0.0f;
  };
  BakedInstance baked_instance(size_t copy) const;
  // What baking cost and how far it strays (mode baked; zeros otherwise).
  struct BakeSummary {
    float rate_hz = 0.0f;
    double bake_ms = 0.0;            // BakeJob over every action of every character
    float max_deviation = 0.0f;      // model units, the worst character
    float max_deviation_fraction = 0.0f;  // of that character's height, the worst character
    uint64_t samples = 0;            // baked palettes, all characters
  };
  const BakeSummary& bake_summary() const { return bake_summary_; }
  // What the renderer said it holds on the GPU for this bench's mode when it
  // prepared for it (FrameRenderer::animation_gpu_bytes); 0 without one.
  uint64_t animation_gpu_bytes() const { return animation_gpu_bytes_; }
  // With --vertex-format packed (skinned_positions() and skinned_normals() are
  // then empty): 3 position codes and one normal word per vertex
  // (skinning/packed_vertex.h), quantised in character_quantisation(kind).
  bool packed_vertices() const { return config_.mode.vertex_format == VertexFormat::Packed; }
  std::span<const uint16_t> packed_positions(size_t copy) const;
  std::span<const uint32_t> packed_normals(size_t copy) const;
  // The box a character's positions are packed in: its animated bounds
  // (every pose of every action, padded), the culling box.
  const PositionQuantisation& character_quantisation(size_t kind) const { return kinds_[kind].quantisation; }

 private:
  // The clock's switch to `category`, recording the stage it leaves when tracing.
  void enter(Category category);
  void update_logic();
  void update_scenegraph(Counters& counters);
  void update_poses(Counters& counters);
  // Who takes a new pose this frame (LOD, budget), at which time (quantum), and
  // which states must be evaluated into which storage: jobs_. Sequential.
  void plan_updates(Counters& counters);
  // The budget's doublings for this frame, from the last frame's time.
  void run_budget();
  void skin_copies();
  // The frame's work by character and in all, from who was posed and where
  // each character is skinned.
  void count_work(Counters& counters);
  // Pose (and, when its character is skinned in Animations, vertices) of one
  // copy; `slot` picks the pose storage.
  // One evaluation: the pose of job.leader's action at job.time, built in pose
  // slot `slot`, written to the job's storage.
  struct StateJob {
    uint32_t leader = 0, storage = 0;
    float time = 0;
  };
  // `skin`: also skin the job's storage when its character is skinned in
  // Animations (else the caller skins it, in parts: skin_range).
  void update_state(const StateJob& job, size_t slot, uint64_t* lookups, bool skin);
  // How many parts update_poses skins each of this frame's states in: 1, or
  // with fewer states than threads (on a parallel mode skinning in
  // Animations) two parts a thread, so that one state keeps every thread busy.
  size_t skin_parts() const;
  // The calling thread's index in the bench's arena (0 without one): which
  // per-thread scratch (model_) a pose update uses.
  size_t worker_index() const;
  void skin_storage(size_t storage);
  // Part `part` of `parts` of a storage's mesh (whole kernel batches).
  void skin_range(size_t storage, size_t part, size_t parts);
  // While `posed` says the state's pose is not built yet, prefetches for
  // writing the skinned vertices from this part to the mesh's end.
  void prefetch_while(size_t storage, size_t part, size_t parts, const std::atomic<uint8_t>& posed) const;
  void skin_vertices(size_t storage, size_t first, size_t count);
  // Mode baked, at load: bakes every character and measures the deviation.
  void bake_characters();
  bool animates(size_t copy) const { return !config_.mode.animation_culling || visible_[copy]; }
  // Animated this frame: not culled, and its character has actions to play
  // (one without stands in its rest pose).
  // Baked copies are never posed on the CPU: the GPU reads their baked samples.
  bool poses(size_t copy) const { return animates(copy) && kind_poses_[crowd_.kind[copy]]; }
  // The pose storage a copy is built in: its own, or its character's scratch.
  size_t slot_of(size_t copy) const {
    return config_.mode.pose == PoseStorage::SharedScratch ? crowd_.kind[copy] : copy;
  }
  // `task` names the spans of its tasks in a trace.
  template <typename Body>
  void for_each_copy(std::string_view task, const Body& body) { for_each_index(task, crowd_.size(), body); }
  template <typename Body>
  void for_each_index(std::string_view task, size_t count, const Body& body);

  // What a character's copies share: its sizes, where it is skinned (the
  // mode's site, except that a character over the GPU's bone limit falls back
  // to the CPU, in Animations) and its actions' bindings, resolved once.
  struct Kind {
    size_t joints = 0, vertices = 0, max_channels = 0;
    SkinningSite site = SkinningSite::CpuInAnimations;
    std::vector<ActionBindings> bindings;  // per action
    SkinningPlan skinning_plan;            // the mesh prepared for skinning, once
    BakedCharacter baked;                  // mode baked only
    PositionQuantisation quantisation;     // packed vertices: the character's box
  };

  std::vector<const Character*> characters_;
  BenchConfig config_;
  Crowd crowd_;
  Camera camera_;
  Frustum frustum_;
  CategoryClock clock_;
  CategoryClock::Clock::time_point frame_start_{}, stage_start_{};  // for the tracer
  size_t frame_ = 0;
  std::vector<Kind> kinds_;                   // per character
  std::vector<uint8_t> kind_poses_;           // per character: has actions and is posed on the CPU (not baked)
  bool skins_in_animations_ = false;          // some character is skinned on the CPU in Animations
  // Per state when its mesh is skinned in parts (fewer states than threads):
  // whether its pose is built yet.
  static constexpr uint8_t kNotPosed = 0, kPosing = 1, kPosed = 2;
  std::unique_ptr<std::atomic<uint8_t>[]> posed_;
  std::vector<Counters> character_counters_;  // per character, the last frame's
  BakeSummary bake_summary_;
  uint64_t animation_gpu_bytes_ = 0;
  std::array<GpuTime, kGpuTimesInFlight> gpu_times_{};
  size_t gpu_time_count_ = 0;

  std::vector<float> times_;                  // per copy: where in its action
  std::vector<uint8_t> visible_;              // per copy, from the last scenegraph stage
  std::vector<SamplingCursor> cursors_;       // per copy
  std::vector<size_t> joint_offset_, vertex_offset_;  // per copy, into palettes_ and positions_/normals_
  std::vector<LocalPose> poses_;              // per pose slot (one per character when shared)
  std::vector<size_t> slot_channels_;         // per pose slot, offsets into targets_
  // Model-space matrices, per thread of the bench x the most joints of a
  // character: an evaluation's intermediate (local-to-model, then the skinning
  // matrices), used at once. Per copy they were 4.4 KiB of the default
  // character's 130 written and read back from memory every frame at 10,000
  // copies. Cache-line aligned (a mat4 is one line), so that no two threads'
  // regions share a line.
  std::vector<glm::mat4, CacheLineAllocator<glm::mat4>> model_;
  size_t model_joints_ = 0, model_threads_ = 1;
  std::vector<int32_t> targets_;              // per pose slot x its channels (string lookups)
  std::vector<SkinMatrix, CacheLineAllocator<SkinMatrix>> palettes_;  // per copy x its joints
  // Per copy x its vertices (float format). Each copy's run starts on a cache
  // line (offsets in whole batches of kSkinBatch vertices, 192 bytes), so that
  // skinning can stream whole lines (stream_output_). Large arrays on huge
  // pages (output_buffer.h).
  std::vector<glm::vec3, CacheLineAllocator<glm::vec3>> positions_, normals_;
  bool stream_output_ = false;  // skinned with streaming stores (output_stores.h)
  std::vector<uint16_t, CacheLineAllocator<uint16_t>> packed_positions_;  // per copy x its vertices x 3 (packed format)
  std::vector<uint32_t, CacheLineAllocator<uint32_t>> packed_normals_;    // per copy x its vertices (packed format)
  // Issue 13: sharing, update rates, the budget.
  std::vector<StateJob> jobs_;                // this frame's evaluations (capacity: one per copy)
  // Sharing, room for every copy: this frame's copies taking a new state, and its key.
  std::vector<uint32_t> changing_copies_;
  std::vector<uint64_t> changing_keys_;
  PoseSharing sharing_;
  std::vector<float> storage_time_;           // per storage: the time it was evaluated at (NaN: rest)
  std::vector<float> screen_fraction_;        // per copy
  std::vector<uint8_t> shift_;                // per copy: updated every 2^shift frames
  std::vector<uint8_t> updated_;              // per copy: took a new pose this frame
  std::vector<int64_t> last_update_;          // per copy: the frame it last took a pose (-1: never)
  BudgetPlan budget_plan_;
  uint64_t last_updates_ = 0;                 // copy updates of the last frame, for the budget
  double last_animations_ms_ = 0;
  UpdateSchedule schedule_;
  // The process's threads for this bench's thread count (bench_threads.h),
  // and their arena; both null when the mode runs on the calling thread alone.
  std::shared_ptr<BenchThreads> threads_;
  tbb::task_arena* arena_ = nullptr;
};

}  // namespace crowdprof
