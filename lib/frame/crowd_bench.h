// The frame loop: a crowd of copies of one or more characters, stepped one
// frame at a time through the BGE's stages in the BGE's order, each charged to
// its profile category by one clock. The loop owns the frame's data and calls
// jobs on it: the characters prepared once (prepared_character.h), the copies'
// arrays (copy_store.h), who is updated (update_plan.h), the pose updates
// (pose_update.h); the renderer draws a FrameView of it (frame_view.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "asset/character.h"
#include "frame/copy_store.h"
#include "frame/frame_renderer.h"
#include "frame/frame_view.h"
#include "base/modes.h"
#include "frame/pose_update.h"
#include "frame/prepared_character.h"
#include "frame/update_plan.h"
#include "measuring/category_clock.h"
#include "measuring/counters.h"
#include "result/result.h"
#include "scene/camera.h"
#include "animation/exact_palette.h"
#include "scene/crowd.h"
#include "scene/transitions.h"
#include "scene/culling_audit.h"

namespace crowdprof {

class Tracer;

struct BenchConfig {
  CrowdOptions crowd;  // groups index the characters the bench is made with
  std::string mode_name = "threaded";
  ModeSwitches mode;
  int threads = 1;    // worker threads when mode.parallel
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
  std::vector<std::string> content_hashes;  // per character: of its file's bytes (bench_setup.h)
  std::string scene_file, scene_hash;
  bool actions_from_scene = false;  // each group's actions as its scene file says
  // For tests of the animation budget: when not empty, the budget's controller
  // reads frame f's Animations time as replay_animations_ms[(f - 1) % size]
  // instead of the clock's, so its choices (and the digest) are reproducible.
  std::vector<double> replay_animations_ms;
};

// Empty when a bench of this config can run, else why not: switches that
// conflict, skinning on the GPU without a renderer, a bake rate that is not a
// positive number.
SettingText why_cannot_run(const BenchConfig& config);

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
  std::string pipeline_statistics_missing() const;
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
  // What the renderer draws: the crowd as the last frame left it.
  const FrameView& view() const { return view_; }
  // The pose storage copy `copy` draws: its own, or with animation sharing
  // that of the state it shows (copies in one state draw one storage).
  size_t storage_of(size_t copy) const { return planner_->storage_of(copy); }
  // Share of the screen's height the copy's box spans (screen_size.h).
  float screen_fraction(size_t copy) const { return planner_->screen_fraction(copy); }
  // How updates were scheduled (sharing, update-rate LOD, the budget) and how
  // faithfully the last frame's copies on screen followed their exact times:
  // the largest distance between a vertex as drawn and where the copy's exact
  // time would put it. Skins every copy on screen twice, so it is for the end
  // of a run (allocates, takes time).
  AnimationRecord measure_animation() const;
  // The last frame against exact, full-detail poses (DrawnErrorRecord, its
  // switches_per_second left to who knows the measured frames), on a
  // screen `screen_height_px` tall; at most `max_copies` copies (fewer for
  // meshes over 5,000 vertices: 2e8 vertices skinned at most; every Nth past
  // that), in parallel on the bench's threads. For the end of a run.
  DrawnErrorRecord measure_drawn_error(int screen_height_px, size_t max_copies = 40000) const;
  const UpdateSchedule& schedule() const { return planner_->schedule(); }
  // Mesh LOD: the level copy `copy` draws (0, the full mesh, without it).
  size_t mesh_level(size_t copy) const { return level_of(copy); }
  // Mesh LOD: per level (kMeshLevels), the copies on screen and the error they
  // are drawn with, on a screen `screen_height_px` tall; all zero without mesh LOD.
  MeshLodRecord mesh_lod_fidelity(int screen_height_px) const;
  // The culling audit (scene/culling_audit.h): at most `max_copy_frames` copy
  // poses (fewer for meshes over 5,000 vertices: 2e8 vertices skinned at
  // most), up to 16 poses a copy spread over the longest action (every
  // copy_stride-th copy past that many copies), on the bench's threads. Exact
  // poses whatever the mode; for the end of a run (allocates, takes time).
  CullingAudit audit_culling(size_t max_copy_frames = kCullingAuditCopyFrames) const;
  static constexpr size_t kCullingAuditCopyFrames = 40000;
  size_t frames_run() const { return frame_; }
  bool visible(size_t copy) const { return store_->visible[copy] != 0; }
  // Where this character's copies are skinned: the mode's site, or the CPU for
  // a character over hwskin's bone limit.
  SkinningSite site_of_kind(size_t kind) const { return prepared_[kind].site; }
  // True when the renderer skins this copy's character (mode hwskin and the
  // character within its bone limit, or compute, or baked): it keeps no
  // vertices on the CPU (skinned_positions() and the others are empty).
  bool gpu_skinned_copy(size_t copy) const { return skins_on_gpu(site_of_kind(crowd_.kind[copy])); }
  // Every character skinned by the renderer.
  bool gpu_skinned() const { return view_.gpu_skinned(); }
  std::span<const SkinMatrix> skinning_matrices(size_t copy) const { return view_.palette(copy); }
  // Float vertices skinned on the CPU are written with streaming stores: the
  // frame's output is larger than the caches (skinning/output_stores.h). Each
  // copy's skinned_positions() and skinned_normals() start on a cache line.
  bool streams_output() const { return store_->stream_output; }
  // Empty with packed vertices (packed_positions(), packed_normals()).
  std::span<const glm::vec3> skinned_positions(size_t copy) const { return view_.skinned_positions(copy); }
  std::span<const glm::vec3> skinned_normals(size_t copy) const { return view_.skinned_normals(copy); }
  // This frame's time of a copy on its action's clock (from the Logic stage).
  float action_time(size_t copy) const { return store_->times[copy]; }
  // What baking cost and how far it strays (mode baked; zeros otherwise).
  const BakeRecord& bake_summary() const { return bake_summary_; }
  // What the renderer said it holds on the GPU for this bench's mode when it
  // prepared for it (FrameRenderer::animation_gpu_bytes); 0 without one.
  uint64_t animation_gpu_bytes() const { return animation_gpu_bytes_; }
  // With a renderer: the GPU's memory as the GL reports it.
  std::optional<GpuMemoryRecord> gpu_memory() const {
    return config_.renderer ? std::optional(config_.renderer->gpu_memory()) : std::nullopt;
  }
  // With --vertex-format packed (skinned_positions() and skinned_normals() are
  // then empty): 3 position codes and one normal word per vertex
  // (skinning/packed_vertex.h), quantised in the character's animated box.
  bool packed_vertices() const { return store_->packed; }
  std::span<const uint16_t> packed_positions(size_t copy) const { return view_.packed_positions_of(copy); }
  std::span<const uint32_t> packed_normals(size_t copy) const { return view_.packed_normals_of(copy); }

 private:
  // The clock's switch to `category`, recording the stage it leaves when tracing.
  void enter(Category category);
  // Logic: each copy's time on its action's clock.
  void update_logic();
  // Animations: the plan, then its evaluations.
  void update_poses(Counters& counters);
  // Scenegraph: who is inside the frustum.
  void update_scenegraph(Counters& counters);
  // Rasterizer, mode baked: where each copy on screen reads its baked table.
  void place_baked_instances();
  // Copy `copy`'s place among the baked samples of its character's action
  // `action` at that action's time `time`.
  BakedInstance baked_instance(size_t copy, size_t action, float time) const;
  // With transitions: the action copy `copy` fades from as its baked record
  // sends it, from the Logic stage's arrays (weight 0: not fading).
  BakedFade baked_fade(size_t copy) const;
  // The action copy `copy` plays this frame: its crowd's, or the schedule's.
  size_t action_now(size_t copy) const { return transitions_ ? store_->actions[copy] : crowd_.action[copy]; }
  // The action time copy `copy` shows `seconds` into the run, on the clock of
  // the action it starts with (with transitions, until its first change).
  float copy_time(size_t copy, double seconds) const;
  // Copy `copy`'s exact palette in the last frame (the reference of the
  // drawn-error and fidelity checks): its action at `time`; with transitions
  // the action it played then (at `time`), blended as its fade stood.
  std::span<const SkinMatrix> exact_palette(size_t copy, float time, ExactPalette& scratch) const;
  // Logic with transitions: each copy's action, time and fade at `t`.
  void update_transitions(double t);
  // Overhead: the frame's work by character and in all, from who was posed
  // and where each character is skinned.
  void count_work(Counters& counters);
  // Animated this frame: not culled (a character without actions, or baked,
  // is never posed on the CPU all the same).
  BakedClock baked_clock(size_t copy) const;
  // frustum gpu: the counters from the GPU's visible counts, per character.
  void count_gpu_culled_work(Counters& counters);
  // The characters' lod*_ counters summed into `counters`.
  void add_lod_counters(Counters& counters) const;
  bool animates(size_t copy) const { return !config_.mode.animation_culling || store_->visible[copy]; }
  // Mesh LOD: each copy's level from its size on screen (copies and camera
  // stand still, so it is chosen once, at load).
  void choose_mesh_levels();
  size_t level_of(size_t copy) const { return mesh_level_.empty() ? 0 : mesh_level_[copy]; }
  // Triangles of a character's mesh level.
  uint64_t triangles_of(size_t kind, size_t level) const;

  std::vector<const Character*> characters_;
  BenchConfig config_;
  Crowd crowd_;
  Camera camera_;
  Frustum frustum_;
  std::vector<glm::mat4> shadow_cameras_;    // passes > 2: one per cascade
  std::vector<PreparedCharacter> prepared_;  // per character; immutable once made
  BakeRecord bake_summary_;
  std::unique_ptr<CopyStore> store_;
  std::unique_ptr<TransitionSchedule> transitions_;  // with --transitions
  std::unique_ptr<UpdatePlanner> planner_;
  std::unique_ptr<PoseUpdater> poser_;
  std::vector<CharacterView> character_views_;
  std::vector<BakedInstance> baked_instances_;  // per copy, mode baked
  std::vector<BakedFade> baked_fades_;          // per copy, mode baked with transitions
  std::vector<BakedClock> baked_clocks_;        // per copy, mode baked with frustum gpu
  std::vector<uint64_t> copies_of_character_;   // per character
  std::vector<uint64_t> gpu_visible_;           // per character and level, frustum gpu: the cull pass's count
  std::vector<uint8_t> mesh_level_;             // per copy, mesh LOD: the level it draws (empty: none)
  bool loaded_ = false;                         // the constructor has finished (its frame -1 is done)
  FrameView view_;
  CategoryClock clock_;
  CategoryClock::Clock::time_point frame_start_{}, stage_start_{};  // for the tracer
  size_t frame_ = 0;
  std::vector<Counters> character_counters_;  // per character, the last frame's
  double last_animations_ms_ = 0;
  uint64_t animation_gpu_bytes_ = 0;
  std::array<GpuTime, kGpuTimesInFlight> gpu_times_{};
  size_t gpu_time_count_ = 0;
};

}  // namespace crowdprof
