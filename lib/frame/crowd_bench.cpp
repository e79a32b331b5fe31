#include "frame/crowd_bench.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "animation/pose.h"
#include "asset/errors.h"
#include "profile/trace.h"
#include "skinning/skinning.h"

namespace crowdprof {

uint64_t estimate_bench_bytes(const Character& c, size_t copies, const ModeSwitches& mode) {
  uint64_t joints = c.skeleton.joint_count(), vertices = c.mesh.vertex_count();
  uint64_t channels = 0;
  for (const Action& a : c.actions) channels = std::max<uint64_t>(channels, a.channels.size());
  uint64_t slots = mode.pose == PoseStorage::SharedScratch ? 1 : copies;
  uint64_t per_copy = joints * sizeof(SkinMatrix) + vertices * 2 * sizeof(glm::vec3) + channels * 4 + 64 +
                      sizeof(glm::mat4) /* world */ + sizeof(Aabb);
  uint64_t per_slot = joints * (sizeof(glm::vec3) * 2 + sizeof(glm::quat) + sizeof(glm::mat4)) + channels * 4;
  return c.shared_bytes() + copies * per_copy + slots * per_slot;
}

std::string why_cannot_run(const BenchConfig& config) {
  std::string conflict = conflicts(config.mode);
  if (!conflict.empty()) return conflict;
  if (config.mode.skinning == SkinningSite::Gpu && !config.renderer)
    return "skinning on the GPU (mode hwskin) needs a GL backend: --backend auto, egl or osmesa";
  return {};
}

CrowdBench::CrowdBench(const Character& character, const BenchConfig& config)
    : character_(character), config_(config) {
  if (std::string why = why_cannot_run(config); !why.empty()) throw UsageError(why);
  skin_site_ = config.mode.skinning;
  // Thesis 4.4: a skeleton too big for the shader's bone array is skinned in software.
  if (skin_site_ == SkinningSite::Gpu && character.skeleton.joint_count() > config.renderer->max_gpu_joints())
    skin_site_ = SkinningSite::CpuInAnimations;
  if (character.actions.empty() && config.crowd.actions == ActionChoice::Random)
    throw UsageError("random actions need a character with actions");
  joints_ = character.skeleton.joint_count();
  vertices_ = character.mesh.vertex_count();
  crowd_ = make_crowd(character, config.crowd);
  camera_ = make_camera(config.camera, crowd_.crowd_box, config.aspect);
  frustum_ = frustum_of(camera_.view_projection());
  size_t n = crowd_.size();

  for (const Action& action : character.actions) {
    bindings_.push_back(bind_action(character.skeleton, action));
    max_channels_ = std::max(max_channels_, action.channels.size());
  }
  times_.assign(n, 0.0f);
  visible_.assign(n, 0);
  cursors_.resize(n);
  for (size_t i = 0; i < n; ++i)
    if (!character.actions.empty()) reset_cursor(character.actions[crowd_.action[i]], &cursors_[i]);
  size_t slots = config.mode.pose == PoseStorage::SharedScratch ? 1 : n;
  poses_.resize(slots);
  for (LocalPose& pose : poses_) reset_to_rest(character.skeleton, &pose);
  model_.resize(slots * joints_);
  targets_.assign(slots * max_channels_, -1);
  palettes_.resize(n * joints_);
  positions_.resize(n * vertices_);
  normals_.resize(n * vertices_);
  // Until a pose is computed, copies show the rest pose.
  LocalPose rest;
  reset_to_rest(character.skeleton, &rest);
  std::vector<glm::mat4> model(joints_);
  LocalToModelJob{&character.skeleton, &rest, model}.Run();
  for (size_t i = 0; i < n; ++i) {
    SkinningMatricesJob{&character.skeleton, model, std::span(palettes_).subspan(i * joints_, joints_)}.Run();
    std::copy(character.mesh.positions.begin(), character.mesh.positions.end(), positions_.begin() + static_cast<std::ptrdiff_t>(i * vertices_));
    std::copy(character.mesh.normals.begin(), character.mesh.normals.end(), normals_.begin() + static_cast<std::ptrdiff_t>(i * vertices_));
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
  double cpu_start = process_cpu_ms();
  Counters& counters = record.counters;
  clock_.begin_frame(Category::Logic);
  if (config_.tracer) frame_start_ = stage_start_ = CategoryClock::Clock::now();
  update_logic();
  enter(Category::Physics);  // no physics in a crowd benchmark
  enter(Category::Animations);
  update_poses(counters);
  enter(Category::Scenegraph);
  update_scenegraph(counters);
  enter(Category::Rasterizer);
  if (skin_site_ == SkinningSite::CpuInRasterizer) skin_copies(counters);
  if (config_.renderer) config_.renderer->draw(*this, counters);
  enter(Category::GpuLatency);  // without a GL backend, nothing to wait for
  if (config_.renderer) config_.renderer->finish();
  enter(Category::Overhead);
  ++frame_;
  // Between frames (reports, progress) is outside the engine's frame.
  enter(Category::Outside);
  if (config_.tracer)
    config_.tracer->span("frame", "frame", frame_start_, stage_start_, config_.trace_pid,
                         {{"frame", static_cast<int64_t>(frame_ - 1)}});
  record.times = clock_.end_frame();
  record.cpu_ms = process_cpu_ms() - cpu_start;
  return record;
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
    if (character_.actions.empty()) break;
    const Action& action = character_.actions[crowd_.action[i]];
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
  if (character_.actions.empty()) return;
  bool skin_here = skin_site_ == SkinningSite::CpuInAnimations;
  bool shared = config_.mode.pose == PoseStorage::SharedScratch;
  uint64_t posed = 0, lookups = 0;
  for (size_t i = 0; i < crowd_.size(); ++i) posed += animates(i);
  if (!arena_) {
    for (size_t i = 0; i < crowd_.size(); ++i)
      if (animates(i)) update_copy(i, shared ? 0 : i, skin_here, &lookups);
  } else {
    std::atomic<uint64_t> total{0};
    for_each_copy(skin_here ? "pose+skin" : "pose", [&](size_t i) {
      if (!animates(i)) return;
      uint64_t mine = 0;
      update_copy(i, i, skin_here, &mine);
      total.fetch_add(mine, std::memory_order_relaxed);
    });
    lookups = total.load();
  }
  counters.poses_updated = posed;
  counters.copies_culled = crowd_.size() - posed;
  counters.channel_lookups = lookups;
  if (skin_here) counters.vertices_skinned = posed * vertices_;
  if (skin_here && config_.mode.skinning == SkinningSite::Gpu) counters.copies_fallback = posed;
}

void CrowdBench::update_copy(size_t copy, size_t slot, bool skin, uint64_t* lookups) {
  const Skeleton& skeleton = character_.skeleton;
  size_t action_index = crowd_.action[copy];
  const Action& action = character_.actions[action_index];
  const ActionBindings& bindings = bindings_[action_index];
  LocalPose& pose = poses_[slot];
  std::span<const int32_t> targets = bindings.targets;
  if (config_.mode.lookups == Lookups::PerFrameString) {
    std::span<int32_t> scratch = std::span(targets_).subspan(slot * max_channels_, action.channels.size());
    size_t count = 0;
    ResolvePathsJob{&skeleton, &bindings, scratch, &count}.Run();
    *lookups += count;
    targets = scratch;
  }
  // A shared scratch pose still holds the previous copy's joints: start from rest,
  // as the BGE's pose swap copied the armature's own pose in.
  if (config_.mode.pose == PoseStorage::SharedScratch) reset_to_rest(skeleton, &pose);
  SamplingJob{&action, times_[copy], targets, &cursors_[copy], &pose}.Run();
  std::span<glm::mat4> model = std::span(model_).subspan(slot * joints_, joints_);
  LocalToModelJob{&skeleton, &pose, model}.Run();
  SkinningMatricesJob{&skeleton, model, std::span(palettes_).subspan(copy * joints_, joints_)}.Run();
  if (skin) skin_copy(copy);
}

void CrowdBench::skin_copy(size_t copy) {
  SkinningJob{std::span<const SkinMatrix>(palettes_).subspan(copy * joints_, joints_), &character_.mesh, 0, vertices_,
              std::span(positions_).subspan(copy * vertices_, vertices_),
              std::span(normals_).subspan(copy * vertices_, vertices_)}
      .Run();
}

void CrowdBench::skin_copies(Counters& counters) {
  uint64_t skinned = 0;
  for (size_t i = 0; i < crowd_.size(); ++i) skinned += animates(i);
  for_each_copy("skin", [&](size_t i) {
    if (animates(i)) skin_copy(i);
  });
  counters.vertices_skinned = skinned * vertices_;
}

std::span<const SkinMatrix> CrowdBench::skinning_matrices(size_t copy) const {
  return std::span(palettes_).subspan(copy * joints_, joints_);
}
std::span<const glm::vec3> CrowdBench::skinned_positions(size_t copy) const {
  return std::span(positions_).subspan(copy * vertices_, vertices_);
}
std::span<const glm::vec3> CrowdBench::skinned_normals(size_t copy) const {
  return std::span(normals_).subspan(copy * vertices_, vertices_);
}

namespace {
void fnv1a(uint64_t& hash, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
}
}  // namespace

std::string CrowdBench::digest() const {
  uint64_t hash = 0xcbf29ce484222325ull;
  bool cpu_skinned = skin_site_ != SkinningSite::Gpu;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!visible_[i]) continue;
    auto palette = skinning_matrices(i);
    fnv1a(hash, palette.data(), palette.size_bytes());
    if (cpu_skinned) {
      fnv1a(hash, skinned_positions(i).data(), skinned_positions(i).size_bytes());
      fnv1a(hash, skinned_normals(i).data(), skinned_normals(i).size_bytes());
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace crowdprof
