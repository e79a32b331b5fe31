#include "frame/crowd_bench.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "animation/pose.h"
#include "asset/errors.h"
#include "profile/trace.h"
#include "skinning/skinning.h"

namespace crowdprof {

namespace {

// What one copy and one pose slot of a character cost.
uint64_t copy_bytes(const Character& c) {
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  return c.skeleton.joint_count() * sizeof(SkinMatrix) + c.mesh.vertex_count() * 2 * sizeof(glm::vec3) +
         channels * 4 + 64 + sizeof(glm::mat4) /* world */ + sizeof(Aabb) + 4 * sizeof(size_t) /* offsets */;
}
uint64_t slot_bytes(const Character& c) {
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  return c.skeleton.joint_count() * (sizeof(glm::vec3) * 2 + sizeof(glm::quat) + sizeof(glm::mat4)) + channels * 4;
}

}  // namespace

uint64_t estimate_bench_bytes(const Character& c, size_t copies, const ModeSwitches& mode) {
  uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies;
  return c.shared_bytes() + copies * copy_bytes(c) + slots * slot_bytes(c);
}

uint64_t estimate_bench_bytes(std::span<const Character* const> characters, const CrowdOptions& crowd,
                              const ModeSwitches& mode) {
  uint64_t bytes = 0;
  std::vector<size_t> copies(characters.size(), 0);
  for (const CrowdGroup& group : crowd_groups(crowd))
    if (group.character < copies.size()) copies[group.character] += group.copies;
  for (size_t k = 0; k < characters.size(); ++k) {
    uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies[k];
    bytes += characters[k]->shared_bytes() + copies[k] * copy_bytes(*characters[k]) + slots * slot_bytes(*characters[k]);
  }
  return bytes;
}

std::string why_cannot_run(const BenchConfig& config) {
  std::string conflict = conflicts(config.mode);
  if (!conflict.empty()) return conflict;
  if (config.mode.skinning == SkinningSite::Gpu && !config.renderer)
    return "skinning on the GPU (mode hwskin) needs a GL backend: --backend auto, egl or osmesa";
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
  character_counters_.resize(characters_.size());
  crowd_ = make_crowd(characters_, config.crowd);
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
    vertices += kind.vertices;
    const Character& character = character_of(i);
    if (!character.actions.empty()) reset_cursor(character.actions[crowd_.action[i]], &cursors_[i]);
  }
  bool shared = config.mode.pose == PoseStorage::SharedScratch;
  size_t slots = shared ? characters_.size() : n;
  poses_.resize(slots);
  slot_joints_.resize(slots);
  slot_channels_.resize(slots);
  size_t slot_joint_total = 0, slot_channel_total = 0;
  for (size_t s = 0; s < slots; ++s) {
    size_t k = shared ? s : crowd_.kind[s];
    reset_to_rest(characters_[k]->skeleton, &poses_[s]);
    slot_joints_[s] = slot_joint_total;
    slot_channels_[s] = slot_channel_total;
    slot_joint_total += kinds_[k].joints;
    slot_channel_total += kinds_[k].max_channels;
  }
  model_.resize(slot_joint_total);
  targets_.assign(slot_channel_total, -1);
  palettes_.resize(joints);
  positions_.resize(vertices);
  normals_.resize(vertices);
  // Until a pose is computed, copies show the rest pose.
  std::vector<std::vector<SkinMatrix>> rest_palettes;
  for (const Character* character : characters_) {
    LocalPose rest;
    reset_to_rest(character->skeleton, &rest);
    std::vector<glm::mat4> model(character->skeleton.joint_count());
    LocalToModelJob{&character->skeleton, &rest, model}.Run();
    rest_palettes.emplace_back(model.size());
    SkinningMatricesJob{&character->skeleton, model, rest_palettes.back()}.Run();
  }
  for (size_t i = 0; i < n; ++i) {
    const SkinnedMesh& mesh = character_of(i).mesh;
    const std::vector<SkinMatrix>& rest = rest_palettes[crowd_.kind[i]];
    std::copy(rest.begin(), rest.end(), palettes_.begin() + static_cast<std::ptrdiff_t>(joint_offset_[i]));
    std::copy(mesh.positions.begin(), mesh.positions.end(), positions_.begin() + static_cast<std::ptrdiff_t>(vertex_offset_[i]));
    std::copy(mesh.normals.begin(), mesh.normals.end(), normals_.begin() + static_cast<std::ptrdiff_t>(vertex_offset_[i]));
  }
  if (config.mode.parallel) {
    auto threads = static_cast<size_t>(std::max(1, config.threads));
    if (threads > tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))
      parallelism_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    arena_ = std::make_unique<tbb::task_arena>(static_cast<int>(threads));
  }
  // The scenegraph of "frame -1": the first frame's animation culling needs it.
  Counters unused;
  update_scenegraph(unused);
}

bool CrowdBench::gpu_skinned() const {
  for (const Kind& kind : kinds_)
    if (kind.site != SkinningSite::Gpu) return false;
  return true;
}

CrowdBench::~CrowdBench() = default;

template <typename Body>
void CrowdBench::for_each_copy(std::string_view task, const Body& body) {
  size_t n = crowd_.size();
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
  return record;
}

void CrowdBench::collect_gpu_times() {
  gpu_time_count_ = config_.renderer ? config_.renderer->take_gpu_times(*this, frame_, gpu_times_, true) : 0;
}

std::string CrowdBench::gpu_timing_missing() const {
  return config_.renderer ? config_.renderer->gpu_timing_missing() : "no GL backend (--backend none)";
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

void CrowdBench::update_poses(Counters& counters) {
  uint64_t lookups = 0;
  if (!arena_) {
    for (size_t i = 0; i < crowd_.size(); ++i)
      if (poses(i)) update_copy(i, slot_of(i), &lookups);
  } else {
    std::atomic<uint64_t> total{0};
    bool skin_here = std::any_of(kinds_.begin(), kinds_.end(),
                                 [](const Kind& kind) { return kind.site == SkinningSite::CpuInAnimations; });
    for_each_copy(skin_here ? "pose+skin" : "pose", [&](size_t i) {
      if (!poses(i)) return;
      uint64_t mine = 0;
      update_copy(i, i, &mine);
      total.fetch_add(mine, std::memory_order_relaxed);
    });
    lookups = total.load();
  }
  counters.channel_lookups = lookups;
}

void CrowdBench::count_work(Counters& counters) {
  for (Counters& c : character_counters_) c = Counters{};
  for (size_t i = 0; i < crowd_.size(); ++i) {
    Counters& c = character_counters_[crowd_.kind[i]];
    c.copies_visible += visible_[i];
    // A character without actions stands in its rest pose: never posed, never culled.
    bool moves = !kinds_[crowd_.kind[i]].bindings.empty();
    c.poses_updated += poses(i);
    c.copies_culled += moves && !animates(i);
  }
  uint64_t posed = 0, culled = 0, skinned = 0, fallback = 0;
  for (size_t k = 0; k < kinds_.size(); ++k) {
    Counters& c = character_counters_[k];
    if (kinds_[k].site != SkinningSite::Gpu) c.vertices_skinned = c.poses_updated * kinds_[k].vertices;
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

void CrowdBench::update_copy(size_t copy, size_t slot, uint64_t* lookups) {
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
    ResolvePathsJob{&skeleton, &bindings, scratch, &count}.Run();
    *lookups += count;
    targets = scratch;
  }
  // A shared scratch pose still holds the previous copy's joints: start from rest,
  // as the BGE's pose swap copied the armature's own pose in.
  if (config_.mode.pose == PoseStorage::SharedScratch) reset_to_rest(skeleton, &pose);
  SamplingJob{&action, times_[copy], targets, &cursors_[copy], &pose}.Run();
  std::span<glm::mat4> model = std::span(model_).subspan(slot_joints_[slot], kind.joints);
  LocalToModelJob{&skeleton, &pose, model}.Run();
  SkinningMatricesJob{&skeleton, model, std::span(palettes_).subspan(joint_offset_[copy], kind.joints)}.Run();
  if (kind.site == SkinningSite::CpuInAnimations) skin_copy(copy);
}

void CrowdBench::skin_copy(size_t copy) {
  const Kind& kind = kinds_[crowd_.kind[copy]];
  SkinningJob{skinning_matrices(copy), &kind.skinning_plan, 0, kind.vertices,
              std::span(positions_).subspan(vertex_offset_[copy], kind.vertices),
              std::span(normals_).subspan(vertex_offset_[copy], kind.vertices)}
      .Run();
}

void CrowdBench::skin_copies() {
  for_each_copy("skin", [&](size_t i) {
    if (poses(i)) skin_copy(i);
  });
}

std::span<const SkinMatrix> CrowdBench::skinning_matrices(size_t copy) const {
  return std::span(palettes_).subspan(joint_offset_[copy], kinds_[crowd_.kind[copy]].joints);
}
std::span<const glm::vec3> CrowdBench::skinned_positions(size_t copy) const {
  return std::span(positions_).subspan(vertex_offset_[copy], kinds_[crowd_.kind[copy]].vertices);
}
std::span<const glm::vec3> CrowdBench::skinned_normals(size_t copy) const {
  return std::span(normals_).subspan(vertex_offset_[copy], kinds_[crowd_.kind[copy]].vertices);
}

namespace {
void fnv1a(uint64_t& hash, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
}
}  // namespace

std::string CrowdBench::digest() const {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!visible_[i]) continue;
    auto palette = skinning_matrices(i);
    fnv1a(hash, palette.data(), palette.size_bytes());
    if (!gpu_skinned_copy(i)) {
      fnv1a(hash, skinned_positions(i).data(), skinned_positions(i).size_bytes());
      fnv1a(hash, skinned_normals(i).data(), skinned_normals(i).size_bytes());
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace crowdprof
