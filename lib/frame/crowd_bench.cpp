#include "frame/crowd_bench.h"
#include "animation/run_job.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "animation/pose.h"
#include "asset/errors.h"
#include "profile/trace.h"
#include "skinning/bake_deviation.h"
#include "skinning/output_stores.h"
#include "scene/screen_size.h"
#include "skinning/skinning.h"

namespace crowdprof {

namespace {

// What one copy and one pose slot of a character cost.
uint64_t copy_bytes(const Character& c, const ModeSwitches& mode) {
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  const uint64_t vertex_bytes = mode.vertex_format == VertexFormat::Packed ? kPackedVertexBytes : kFloatVertexBytes;
  // Each copy's vertices start on a whole batch (the constructor's vertex offsets).
  const uint64_t vertices = (c.mesh.vertex_count() + kSkinBatch - 1) / kSkinBatch * kSkinBatch;
  return c.skeleton.joint_count() * sizeof(SkinMatrix) + vertices * vertex_bytes +
         channels * 4 + 64 + sizeof(glm::mat4) /* world */ + sizeof(Aabb) + 4 * sizeof(size_t) /* offsets */;
}
uint64_t slot_bytes(const Character& c) {
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  // Model-space matrices are per thread, not per slot: a few KiB in all.
  return c.skeleton.joint_count() * (sizeof(glm::vec3) * 2 + sizeof(glm::quat)) + channels * 4;
}

}  // namespace

uint64_t estimate_bench_bytes(const Character& c, size_t copies, const ModeSwitches& mode) {
  uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies;
  return c.shared_bytes() + copies * copy_bytes(c, mode) + slots * slot_bytes(c);
}

uint64_t estimate_bench_bytes(std::span<const Character* const> characters, const CrowdOptions& crowd,
                              const ModeSwitches& mode) {
  uint64_t bytes = 0;
  std::vector<size_t> copies(characters.size(), 0);
  for (const CrowdGroup& group : crowd_groups(crowd))
    if (group.character < copies.size()) copies[group.character] += group.copies;
  for (size_t k = 0; k < characters.size(); ++k) {
    uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies[k];
    bytes += characters[k]->shared_bytes() + copies[k] * copy_bytes(*characters[k], mode) + slots * slot_bytes(*characters[k]);
  }
  return bytes;
}

std::string why_cannot_run(const BenchConfig& config) {
  std::string conflict = conflicts(config.mode);
  if (!conflict.empty()) return conflict;
  if (skins_on_gpu(config.mode.skinning) && !config.renderer)
    return "skinning on the GPU (skinning " + std::string(to_string(config.mode.skinning)) +
           ") needs a GL backend: --backend auto, egl or osmesa";
  if (config.mode.skinning == SkinningSite::Baked && !(config.bake_rate_hz > 0.0f && config.bake_rate_hz <= 10000.0f))
    return "--bake-rate " + std::to_string(config.bake_rate_hz) + ": expected 0 to 10000 samples per second";
  return {};
}

CrowdBench::CrowdBench(const Character& character, const BenchConfig& config)
    : CrowdBench(std::span<const Character* const>(std::array<const Character*, 1>{&character}), config) {}

CrowdBench::CrowdBench(std::span<const Character* const> characters, const BenchConfig& config)
    : characters_(characters.begin(), characters.end()), config_(config) {
  if (std::string why = why_cannot_run(config); !why.empty()) throw UsageError(why);
  if (config.renderer) config.renderer->require(config.mode);
  if (characters_.empty()) throw UsageError("a crowd needs at least one character");
  for (const CrowdGroup& group : crowd_groups(config.crowd)) {
    if (group.character >= characters_.size()) throw UsageError("a crowd group names a character that is not there");
    if (characters_[group.character]->actions.empty() && group.actions != ActionChoice::Shared)
      throw UsageError("random actions need a character with actions");
  }
  for (const Character* character : characters_) {
    Kind kind;
    kind.joints = character->skeleton.joint_count();
    kind.vertices = character->mesh.vertex_count();
    kind.site = config.mode.skinning;
    // Thesis 4.4: a skeleton too big for the shader's bone array is skinned in software.
    if (kind.site == SkinningSite::Gpu && kind.joints > config.renderer->max_gpu_joints(config.mode))
      kind.site = SkinningSite::CpuInAnimations;
    if (std::string why = build_skinning_plan(character->mesh, kind.joints, &kind.skinning_plan); !why.empty())
      throw std::runtime_error("skinning plan: " + why);  // the loader checked the same: a bug if reached
    for (const Action& action : character->actions) {
      kind.bindings.push_back(bind_action(character->skeleton, action));
      kind.max_channels = std::max(kind.max_channels, action.channels.size());
    }
    kinds_.push_back(std::move(kind));
  }
  for (const Kind& kind : kinds_) {
    kind_poses_.push_back(!kind.bindings.empty() && kind.site != SkinningSite::Baked);
    skins_in_animations_ = skins_in_animations_ || kind.site == SkinningSite::CpuInAnimations;
  }
  character_counters_.resize(characters_.size());
  crowd_ = make_crowd(characters_, config.crowd);
  for (size_t k = 0; k < kinds_.size(); ++k)
    kinds_[k].quantisation = position_quantisation(crowd_.character_boxes[k].min, crowd_.character_boxes[k].max);
  camera_ = make_camera(config.camera, crowd_.crowd_box, config.aspect, config.lens);
  frustum_ = frustum_of(camera_.view_projection());
  size_t n = crowd_.size();

  times_.assign(n, 0.0f);
  visible_.assign(n, 0);
  cursors_.resize(n);
  joint_offset_.resize(n);
  vertex_offset_.resize(n);
  size_t joints = 0, vertices = 0;
  for (size_t i = 0; i < n; ++i) {
    const Kind& kind = kinds_[crowd_.kind[i]];
    joint_offset_[i] = joints;
    vertex_offset_[i] = vertices;
    joints += kind.joints;
    vertices += (kind.vertices + kSkinBatch - 1) / kSkinBatch * kSkinBatch;  // the next copy on a cache line
    const Character& character = character_of(i);
    if (!character.actions.empty()) reset_cursor(character.actions[crowd_.action[i]], &cursors_[i]);
  }
  bool shared = config.mode.pose == PoseStorage::SharedScratch;
  size_t slots = shared ? characters_.size() : n;
  poses_.resize(slots);
  slot_channels_.resize(slots);
  size_t slot_channel_total = 0;
  for (size_t s = 0; s < slots; ++s) {
    size_t k = shared ? s : crowd_.kind[s];
    reset_to_rest(characters_[k]->skeleton, &poses_[s]);
    slot_channels_[s] = slot_channel_total;
    slot_channel_total += kinds_[k].max_channels;
  }
  const size_t threads = config.mode.parallel ? static_cast<size_t>(std::max(1, config.threads)) : 1;
  for (const Kind& kind : kinds_) model_joints_ = std::max(model_joints_, kind.joints);
  model_threads_ = config.mode.parallel ? arena_slots(threads) : 1;
  model_.resize(model_joints_ * model_threads_);
  targets_.assign(slot_channel_total, -1);
  palettes_.resize(joints);
  const bool packed = packed_vertices();
  stream_output_ = !packed && stream_skinned_output(vertices * kFloatVertexBytes);
  positions_.resize(packed ? 0 : vertices);
  normals_.resize(packed ? 0 : vertices);
  packed_positions_.resize(packed ? 3 * vertices : 0);
  packed_normals_.resize(packed ? vertices : 0);
  // Until a pose is computed, copies show the rest pose.
  std::vector<std::vector<SkinMatrix>> rest_palettes;
  for (const Character* character : characters_) {
    LocalPose rest;
    reset_to_rest(character->skeleton, &rest);
    std::vector<glm::mat4> model(character->skeleton.joint_count());
    run_job(LocalToModelJob{&character->skeleton, &rest, model}, "LocalToModelJob");
    rest_palettes.emplace_back(model.size());
    run_job(SkinningMatricesJob{&character->skeleton, model, rest_palettes.back()}, "SkinningMatricesJob");
  }
  for (size_t i = 0; i < n; ++i) {
    const SkinnedMesh& mesh = character_of(i).mesh;
    const std::vector<SkinMatrix>& rest = rest_palettes[crowd_.kind[i]];
    std::copy(rest.begin(), rest.end(), palettes_.begin() + static_cast<std::ptrdiff_t>(joint_offset_[i]));
    if (packed) {
      const PositionQuantisation& q = kinds_[crowd_.kind[i]].quantisation;
      for (size_t v = 0; v < mesh.vertex_count(); ++v) {
        quantise_position(q, mesh.positions[v], &packed_positions_[3 * (vertex_offset_[i] + v)]);
        packed_normals_[vertex_offset_[i] + v] = pack_normal(mesh.normals[v]);
      }
      continue;
    }
    std::copy(mesh.positions.begin(), mesh.positions.end(), positions_.begin() + static_cast<std::ptrdiff_t>(vertex_offset_[i]));
    std::copy(mesh.normals.begin(), mesh.normals.end(), normals_.begin() + static_cast<std::ptrdiff_t>(vertex_offset_[i]));
  }
  // Issue 13: who is updated how often, and the storage each copy draws.
  storage_time_.assign(n, std::numeric_limits<float>::quiet_NaN());
  jobs_.reserve(n);
  updated_.assign(n, 0);
  last_update_.assign(n, -1);
  screen_fraction_.resize(n);
  shift_.assign(n, 0);
  glm::mat4 view_projection = camera_.view_projection();
  const LodThresholds& lod = config.mode.lod;
  for (size_t i = 0; i < n; ++i) {
    screen_fraction_[i] = screen_height_fraction(view_projection, crowd_.world_boxes[i]);
    if (config.mode.update_lod) shift_[i] = lod_shift(screen_fraction_[i], lod.every_1, lod.every_2, lod.every_4);
  }
  if (config.mode.share_poses) {
    sharing_.reset(crowd_.kind, characters_.size());
    changing_copies_.resize(n);
    changing_keys_.resize(n);
  }
  if (config.mode.parallel) {
    threads_ = bench_threads(threads);
    arena_ = threads_->arena.get();
    posed_ = std::make_unique<std::atomic<uint8_t>[]>(threads);  // skin_parts(): fewer states than threads
  }
  if (config.mode.skinning == SkinningSite::Baked) bake_characters();
  // The scenegraph of "frame -1": the first frame's animation culling needs it.
  Counters unused;
  update_scenegraph(unused);
  if (config.mode.anim_budget_ms > 0) {
    // Copies stand still and the camera too: who is posed, and how big, is
    // known now and for good.
    std::vector<uint8_t> eligible(n);
    for (size_t i = 0; i < n; ++i) eligible[i] = poses(i);
    budget_plan_ = make_budget_plan(screen_fraction_, shift_, eligible);
  }
  if (config.renderer) {
    config.renderer->prepare(*this);
    animation_gpu_bytes_ = config.renderer->animation_gpu_bytes();
  }
}

void CrowdBench::bake_characters() {
  bake_summary_.rate_hz = config_.bake_rate_hz;
  for (size_t k = 0; k < characters_.size(); ++k) {
    const Character& character = *characters_[k];
    Kind& kind = kinds_[k];
    std::vector<std::span<const int32_t>> targets;
    for (const ActionBindings& b : kind.bindings) targets.emplace_back(b.targets);
    auto start = std::chrono::steady_clock::now();
    if (!bake_character(character, targets, config_.bake_rate_hz, &kind.baked))
      throw std::runtime_error("baking " + character.name + " failed");  // bindings sized by the loader: a bug
    bake_summary_.bake_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (character.actions.empty()) {
      // Stands at rest: its rest palette twice, one interval (the shader's
      // table has the same shape for every character).
      kind.baked.first_sample = {0};
      kind.baked.intervals = {1};
      LocalPose rest;
      reset_to_rest(character.skeleton, &rest);
      std::vector<glm::mat4> model(kind.joints);
      run_job(LocalToModelJob{&character.skeleton, &rest, model}, "LocalToModelJob");
      kind.baked.matrices.resize(2 * kind.joints);
      run_job(SkinningMatricesJob{&character.skeleton, model, std::span(kind.baked.matrices).first(kind.joints)},
              "SkinningMatricesJob");
      std::copy_n(kind.baked.matrices.begin(), kind.joints, kind.baked.matrices.begin() + static_cast<std::ptrdiff_t>(kind.joints));
    }
    bake_summary_.samples += kind.baked.samples();
    BakeDeviation d = measure_bake_deviation(character, targets, kind.baked, kind.skinning_plan);
    bake_summary_.max_deviation = std::max(bake_summary_.max_deviation, d.model_units);
    bake_summary_.max_deviation_fraction = std::max(bake_summary_.max_deviation_fraction, d.fraction_of_height());
  }
}

CrowdBench::BakedInstance CrowdBench::baked_instance(size_t copy) const {
  const Kind& kind = kinds_[crowd_.kind[copy]];
  BakedInstance instance;
  if (!kind.baked.joints) return instance;
  const Character& character = character_of(copy);
  size_t a = character.actions.empty() ? 0 : crowd_.action[copy];
  instance.first_sample = static_cast<uint32_t>(kind.baked.first_sample[a]);
  instance.intervals = static_cast<uint32_t>(kind.baked.intervals[a]);
  instance.position = character.actions.empty() ? 0.0f
                                                : baked_position(character.actions[a], kind.baked.intervals[a], times_[copy]);
  return instance;
}

bool CrowdBench::gpu_skinned() const {
  for (const Kind& kind : kinds_)
    if (!skins_on_gpu(kind.site)) return false;
  return true;
}

CrowdBench::~CrowdBench() = default;

template <typename Body>
void CrowdBench::for_each_index(std::string_view task, size_t n, const Body& body) {
  if (!arena_) {
    for (size_t i = 0; i < n; ++i) body(i);
    return;
  }
  // One copy per task: a copy is tens of microseconds of work, enough to pay
  // for the task, and fine grains balance copies that are culled.
  arena_->execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1), [&](const tbb::blocked_range<size_t>& range) {
      if (!config_.tracer) {
        for (size_t i = range.begin(); i != range.end(); ++i) body(i);
        return;
      }
      auto start = CategoryClock::Clock::now();
      for (size_t i = range.begin(); i != range.end(); ++i) body(i);
      config_.tracer->span(task, "task", start, CategoryClock::Clock::now(), config_.trace_pid,
                           {{"first_copy", static_cast<int64_t>(range.begin())},
                            {"copies", static_cast<int64_t>(range.size())}});
    });
  });
}

namespace {
double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}
}  // namespace

FrameRecord CrowdBench::step() {
  FrameRecord record;
  Counters& counters = record.counters;
  clock_.begin_frame(Category::Logic);
  double cpu_start = process_cpu_ms();  // inside the frame, so the clock counts its cost
  if (config_.tracer) frame_start_ = stage_start_ = CategoryClock::Clock::now();
  update_logic();
  enter(Category::Physics);  // no physics in a crowd benchmark
  enter(Category::Animations);
  update_poses(counters);
  enter(Category::Scenegraph);
  update_scenegraph(counters);
  enter(Category::Rasterizer);
  if (config_.mode.skinning == SkinningSite::CpuInRasterizer) skin_copies();
  if (config_.renderer) config_.renderer->draw(*this, counters);
  enter(Category::GpuLatency);  // without a GL backend, nothing to wait for
  if (config_.renderer) config_.renderer->finish();
  enter(Category::Overhead);
  count_work(counters);
  // Timer queries of earlier frames that have finished; never waits for one.
  gpu_time_count_ = config_.renderer ? config_.renderer->take_gpu_times(*this, frame_, gpu_times_, false) : 0;
  ++frame_;
  // Between frames (reports, progress) is outside the engine's frame.
  enter(Category::Outside);
  if (config_.tracer)
    config_.tracer->span("frame", "frame", frame_start_, stage_start_, config_.trace_pid,
                         {{"frame", static_cast<int64_t>(frame_ - 1)}});
  record.cpu_ms = process_cpu_ms() - cpu_start;
  record.times = clock_.end_frame();
  last_animations_ms_ = record.times.ms[static_cast<size_t>(Category::Animations)];
  last_updates_ = counters.copies_updated;
  return record;
}

void CrowdBench::collect_gpu_times() {
  gpu_time_count_ = config_.renderer ? config_.renderer->take_gpu_times(*this, frame_, gpu_times_, true) : 0;
}

std::string CrowdBench::gpu_timing_missing() const {
  return config_.renderer ? config_.renderer->gpu_timing_missing() : "no GL backend (--backend none)";
}

double CrowdBench::gpu_timer_resolution_ms() const {
  return config_.renderer ? config_.renderer->gpu_timer_resolution_ms() : 0;
}

void CrowdBench::enter(Category category) {
  Category left = clock_.switch_to(category);
  if (!config_.tracer) return;
  auto now = CategoryClock::Clock::now();
  config_.tracer->span(category_name(left), "stage", stage_start_, now, config_.trace_pid);
  stage_start_ = now;
}

void CrowdBench::update_logic() {
  double t = static_cast<double>(frame_) / config_.fps;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    const Character& character = character_of(i);
    if (character.actions.empty()) continue;
    const Action& action = character.actions[crowd_.action[i]];
    double duration = action.duration();
    double local = duration > 0 ? std::fmod(static_cast<double>(crowd_.phase[i]) + t, duration) : 0.0;
    times_[i] = action.start + static_cast<float>(local);
  }
}

void CrowdBench::update_scenegraph(Counters& counters) {
  uint64_t visible = 0;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    visible_[i] = intersects(frustum_, crowd_.world_boxes[i]) ? 1 : 0;
    visible += visible_[i];
  }
  counters.copies_visible = visible;
}

void CrowdBench::run_budget() {
  if (config_.mode.anim_budget_ms <= 0 || frame_ == 0) return;
  const std::vector<double>& replay = config_.replay_animations_ms;
  double measured = replay.empty() ? last_animations_ms_ : replay[(frame_ - 1) % replay.size()];
  run_job(AnimBudgetJob{&budget_plan_, config_.mode.anim_budget_ms, measured, last_updates_, &schedule_.demotions},
          "AnimBudgetJob");
  for (size_t r = 0; r < budget_plan_.size(); ++r)
    shift_[budget_plan_.order[r]] = budget_plan_.demoted_shift(r, schedule_.demotions);
}

void CrowdBench::plan_updates(Counters& counters) {
  run_budget();
  jobs_.clear();
  size_t changes = 0;  // copies taking a new state: changing_copies_, changing_keys_
  const bool share = config_.mode.share_poses;
  const double quantum = config_.mode.share_quantum_s;
  const bool culling = config_.mode.animation_culling;
  const auto frame = static_cast<int64_t>(frame_);
  // Tallied in locals and stored once: the loop runs per copy, every frame.
  std::array<uint64_t, kRateCount> by_rate{}, updates_by_rate{};
  uint64_t held = 0, longest_gap = schedule_.longest_gap, every_frame = 0, updated_every_frame = 0;
  const size_t n = crowd_.size();
  for (size_t i = 0; i < n; ++i) {
    updated_[i] = 0;
    // poses(i), with the character's part read from one byte.
    if (!kind_poses_[crowd_.kind[i]] || (culling && !visible_[i])) continue;
    const uint8_t shift = shift_[i];
    // Most copies are updated every frame: that count lives in a register.
    if (shift == 0) ++every_frame; else ++by_rate[shift];
    // Copy i takes its turn at offset i: neighbours of one period alternate.
    const int64_t last = last_update_[i];
    if (!update_due(frame_, last, shift, i)) {
      ++held;
      continue;
    }
    if (last >= 0) longest_gap = std::max<uint64_t>(longest_gap, frame - last);
    last_update_[i] = frame;
    updated_[i] = 1;
    if (shift == 0) ++updated_every_frame; else ++updates_by_rate[shift];
    float time = times_[i];
    if (quantum > 0) {
      // The nearest multiple of the quantum from the action's start, never past its end.
      const Action& action = character_of(i).actions[crowd_.action[i]];
      double steps = std::nearbyint(static_cast<double>(time - action.start) / quantum);
      time = std::min(action.end, action.start + static_cast<float>(steps * quantum));
    }
    if (!share) {
      jobs_.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(i), time});
      continue;
    }
    uint32_t bits;
    std::memcpy(&bits, &time, sizeof bits);
    uint64_t key = state_key(crowd_.kind[i], crowd_.action[i], bits);
    if (sharing_.key_of(sharing_.shown(i)) == key) continue;  // still in the state it shows
    changing_copies_[changes] = static_cast<uint32_t>(i);
    changing_keys_[changes++] = key;
  }
  by_rate[0] = every_frame;
  updates_by_rate[0] = updated_every_frame;
  schedule_.copies_by_rate = by_rate;
  schedule_.longest_gap = longest_gap;
  counters.copies_held += held;
  for (size_t r = 0; r < kRateCount; ++r) {
    counters.copies_updated += updates_by_rate[r];
    counters.*kUpdatesByShift[r] += updates_by_rate[r];
  }
  if (!share) return;
  // Every release before any take: a state that one copy leaves and another
  // enters this frame keeps its storage, and there is always room.
  std::span<const uint32_t> copies = std::span(changing_copies_).first(changes);
  sharing_.release(copies);
  for (size_t c = 0; c < changes;) {
    // Copies taking one key one after another (a shared action: all of them).
    const uint64_t key = changing_keys_[c];
    size_t end = c + 1;
    while (end < changes && changing_keys_[end] == key) ++end;
    bool evaluate = false;
    uint32_t storage = sharing_.take(copies.subspan(c, end - c), key, &evaluate);
    float time;
    auto bits = static_cast<uint32_t>(key);
    std::memcpy(&time, &bits, sizeof time);
    if (evaluate) jobs_.push_back({copies[c], storage, time});
    c = end;
  }
}

void CrowdBench::update_poses(Counters& counters) {
  plan_updates(counters);
  uint64_t lookups = 0;
  if (!arena_) {
    for (const StateJob& job : jobs_) update_state(job, slot_of(job.leader), &lookups, true);
  } else if (size_t parts = skin_parts(); parts > 1) {
    // Fewer states than threads (sharing: often one a frame): each state's
    // mesh is skinned in parts, so that every thread has a share. One parallel
    // loop over the parts, so that workers are woken while the first pose is
    // built: the first task of a state to start builds its pose, the others
    // wait for it (for a thread that is running it, never for a queued task).
    std::atomic<uint64_t> total{0};
    for (size_t j = 0; j < jobs_.size(); ++j) posed_[j].store(kNotPosed, std::memory_order_relaxed);
    for_each_index("pose+skin part", jobs_.size() * parts, [&](size_t t) {
      const size_t j = t / parts;
      uint8_t expected = kNotPosed;
      if (posed_[j].compare_exchange_strong(expected, kPosing, std::memory_order_acq_rel)) {
        uint64_t mine = 0;
        update_state(jobs_[j], jobs_[j].leader, &mine, false);
        total.fetch_add(mine, std::memory_order_relaxed);
        posed_[j].store(kPosed, std::memory_order_release);
      } else if (posed_[j].load(std::memory_order_acquire) != kPosed) {
        // Meanwhile, the memory this part writes is brought in (storages
        // taken for new states have not been written for many frames).
        prefetch_while(jobs_[j].storage, t % parts, parts, posed_[j]);
        while (posed_[j].load(std::memory_order_acquire) != kPosed) std::this_thread::yield();
      }
      skin_range(jobs_[j].storage, t % parts, parts);
    });
    lookups = total.load();
  } else {
    std::atomic<uint64_t> total{0};
    bool skin_here = std::any_of(kinds_.begin(), kinds_.end(),
                                 [](const Kind& kind) { return kind.site == SkinningSite::CpuInAnimations; });
    for_each_index(skin_here ? "pose+skin" : "pose", jobs_.size(), [&](size_t j) {
      uint64_t mine = 0;
      update_state(jobs_[j], jobs_[j].leader, &mine, true);
      // Only string lookups count anything: an add of 0 per copy would still
      // pull the counter's cache line back and forth between the threads.
      if (mine != 0) total.fetch_add(mine, std::memory_order_relaxed);
    });
    lookups = total.load();
  }
  counters.channel_lookups = lookups;
}

size_t CrowdBench::skin_parts() const {
  const auto threads = static_cast<size_t>(std::max(1, config_.threads));
  if (!arena_ || jobs_.empty() || jobs_.size() >= threads || !skins_in_animations_) return 1;
  // Two parts a thread: a worker that wakes late still finds one to take.
  return (4 * threads + jobs_.size() - 1) / jobs_.size();
}

void CrowdBench::count_work(Counters& counters) {
  for (Counters& c : character_counters_) c = Counters{};
  for (size_t i = 0; i < crowd_.size(); ++i) {
    Counters& c = character_counters_[crowd_.kind[i]];
    c.copies_visible += visible_[i];
    // A character without actions stands in its rest pose: never posed, never culled.
    bool moves = !kinds_[crowd_.kind[i]].bindings.empty();
    c.copies_culled += moves && !animates(i);
    c.copies_updated += updated_[i];
    c.copies_held += poses(i) && !updated_[i];
    if (updated_[i]) ++(c.*kUpdatesByShift[shift_[i]]);
  }
  // An evaluation is one pose sampled and rebuilt, and one mesh skinned on the CPU.
  for (const StateJob& job : jobs_) ++character_counters_[crowd_.kind[job.leader]].poses_updated;
  uint64_t posed = 0, culled = 0, skinned = 0, fallback = 0;
  for (size_t k = 0; k < kinds_.size(); ++k) {
    Counters& c = character_counters_[k];
    if (!skins_on_gpu(kinds_[k].site)) c.vertices_skinned = c.poses_updated * kinds_[k].vertices;
    if (kinds_[k].site != SkinningSite::Gpu && config_.mode.skinning == SkinningSite::Gpu)
      c.copies_fallback = c.poses_updated;
    posed += c.poses_updated;
    culled += c.copies_culled;
    skinned += c.vertices_skinned;
    fallback += c.copies_fallback;
  }
  counters.poses_updated = posed;
  counters.copies_culled = culled;
  counters.vertices_skinned = skinned;
  counters.copies_fallback = fallback;
}

void CrowdBench::update_state(const StateJob& job, size_t slot, uint64_t* lookups, bool skin) {
  const size_t copy = job.leader;
  const Character& character = character_of(copy);
  const Kind& kind = kinds_[crowd_.kind[copy]];
  const Skeleton& skeleton = character.skeleton;
  size_t action_index = crowd_.action[copy];
  const Action& action = character.actions[action_index];
  const ActionBindings& bindings = kind.bindings[action_index];
  LocalPose& pose = poses_[slot];
  std::span<const int32_t> targets = bindings.targets;
  if (config_.mode.lookups == Lookups::PerFrameString) {
    std::span<int32_t> scratch = std::span(targets_).subspan(slot_channels_[slot], action.channels.size());
    size_t count = 0;
    run_job(ResolvePathsJob{&skeleton, &bindings, scratch, &count}, "ResolvePathsJob");
    *lookups += count;
    targets = scratch;
  }
  // A shared scratch pose still holds the previous copy's joints: start from rest,
  // as the BGE's pose swap copied the armature's own pose in.
  if (config_.mode.pose == PoseStorage::SharedScratch) reset_to_rest(skeleton, &pose);
  // The leader's own cursor: its action, and its time moving forward.
  run_job(SamplingJob{&action, job.time, targets, &cursors_[copy], &pose}, "SamplingJob");
  std::span<glm::mat4> model = std::span(model_).subspan(worker_index() * model_joints_, kind.joints);
  run_job(LocalToModelJob{&skeleton, &pose, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model, std::span(palettes_).subspan(joint_offset_[job.storage], kind.joints)},
          "SkinningMatricesJob");
  storage_time_[job.storage] = job.time;
  if (skin && kind.site == SkinningSite::CpuInAnimations) skin_storage(job.storage);
}

size_t CrowdBench::worker_index() const {
  if (!arena_) return 0;
  // The arena's slot of the calling thread: unique among the threads in it,
  // below arena_slots() (bench_threads.h), for as long as the task runs.
  const int slot = tbb::this_task_arena::current_thread_index();
  if (slot < 0 || static_cast<size_t>(slot) >= model_threads_)
    throw std::logic_error("a pose update outside the bench's arena");
  return static_cast<size_t>(slot);
}

void CrowdBench::skin_storage(size_t storage) {
  skin_vertices(storage, 0, kinds_[crowd_.kind[storage]].vertices);
}

namespace {
// Part `part` of `parts` of a mesh's vertices, [first, end): whole batches of
// the skinning kernels (16 vertices), which give the same bits for any split
// (skinning.h).
std::pair<size_t, size_t> part_of(size_t vertices, size_t part, size_t parts) {
  const size_t batches = (vertices + kSkinBatch - 1) / kSkinBatch;
  return {std::min(vertices, part * batches / parts * kSkinBatch),
          std::min(vertices, (part + 1) * batches / parts * kSkinBatch)};
}

// Asks for the cache lines of [begin, end) to be fetched for writing.
void prefetch_for_write(const void* begin, const void* end) {
  for (auto p = reinterpret_cast<uintptr_t>(begin) & ~uintptr_t{63}; p < reinterpret_cast<uintptr_t>(end); p += 64)
    __builtin_prefetch(reinterpret_cast<const void*>(p), 1, 3);
}
}  // namespace

void CrowdBench::skin_range(size_t storage, size_t part, size_t parts) {
  const Kind& kind = kinds_[crowd_.kind[storage]];
  if (kind.site != SkinningSite::CpuInAnimations) return;  // skinned elsewhere (a mixed crowd)
  auto [first, end] = part_of(kind.vertices, part, parts);
  skin_vertices(storage, first, end - first);
}

void CrowdBench::prefetch_while(size_t storage, size_t part, size_t parts, const std::atomic<uint8_t>& posed) const {
  const Kind& kind = kinds_[crowd_.kind[storage]];
  if (kind.site != SkinningSite::CpuInAnimations) return;
  const size_t v = vertex_offset_[storage];
  // Positions and normals side by side, 64 vertices at a time (that many
  // floats or codes span whole cache lines), from this part to the mesh's end.
  constexpr size_t kStep = 64;
  for (size_t first = part_of(kind.vertices, part, parts).first; first < kind.vertices; first += kStep) {
    if (posed.load(std::memory_order_acquire) == kPosed) return;
    const size_t end = std::min(kind.vertices, first + kStep);
    if (packed_vertices()) {
      prefetch_for_write(&packed_positions_[3 * (v + first)], &packed_positions_[3 * (v + end)]);
      prefetch_for_write(&packed_normals_[v + first], &packed_normals_[v + end]);
    } else {
      prefetch_for_write(&positions_[v + first], &positions_[v + end]);
      prefetch_for_write(&normals_[v + first], &normals_[v + end]);
    }
  }
}

void CrowdBench::skin_vertices(size_t storage, size_t first, size_t count) {
  if (count == 0) return;
  const Kind& kind = kinds_[crowd_.kind[storage]];
  const size_t v = vertex_offset_[storage] + first;
  if (packed_vertices()) {
    run_job(PackedSkinningJob{std::span(palettes_).subspan(joint_offset_[storage], kind.joints), &kind.skinning_plan,
                              &kind.quantisation, first, count,
                              std::span(packed_positions_).subspan(3 * v, 3 * count),
                              std::span(packed_normals_).subspan(v, count)},
            "PackedSkinningJob");
    return;
  }
  run_job(SkinningJob{std::span(palettes_).subspan(joint_offset_[storage], kind.joints), &kind.skinning_plan, first, count,
                      std::span(positions_).subspan(v, count), std::span(normals_).subspan(v, count), stream_output_},
          "SkinningJob");
}

void CrowdBench::skin_copies() {
  for_each_index("skin", jobs_.size(), [&](size_t j) { skin_storage(jobs_[j].storage); });
}

// A copy draws its storage (its own, or its shared state's: the same character).
std::span<const SkinMatrix> CrowdBench::skinning_matrices(size_t copy) const {
  return std::span(palettes_).subspan(joint_offset_[storage_of(copy)], kinds_[crowd_.kind[copy]].joints);
}
std::span<const uint16_t> CrowdBench::packed_positions(size_t copy) const {
  if (!packed_vertices()) return {};
  return std::span(packed_positions_).subspan(3 * vertex_offset_[storage_of(copy)], 3 * kinds_[crowd_.kind[copy]].vertices);
}
std::span<const uint32_t> CrowdBench::packed_normals(size_t copy) const {
  if (!packed_vertices()) return {};
  return std::span(packed_normals_).subspan(vertex_offset_[storage_of(copy)], kinds_[crowd_.kind[copy]].vertices);
}
std::span<const glm::vec3> CrowdBench::skinned_positions(size_t copy) const {
  if (packed_vertices()) return {};
  return std::span(positions_).subspan(vertex_offset_[storage_of(copy)], kinds_[crowd_.kind[copy]].vertices);
}
std::span<const glm::vec3> CrowdBench::skinned_normals(size_t copy) const {
  if (packed_vertices()) return {};
  return std::span(normals_).subspan(vertex_offset_[storage_of(copy)], kinds_[crowd_.kind[copy]].vertices);
}

}  // namespace crowdprof
