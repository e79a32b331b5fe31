#include "frame/pose_update.h"

#include <algorithm>
#include <stdexcept>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "animation/blending.h"
#include "animation/pose.h"
#include "animation/run_job.h"
#include "measuring/category_clock.h"
#include "measuring/trace.h"
#include "skinning/skinning.h"

namespace crowdprof {

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

PoseUpdater::PoseUpdater(const PoseUpdateContext& context)
    : context_(context), crowd_(*context.crowd), store_(*context.store) {
  for (const PreparedCharacter& p : context.prepared) {
    skins_in_animations_ = skins_in_animations_ || p.site == SkinningSite::CpuInAnimations;
    model_joints_ = std::max(model_joints_, p.joints);
  }
  const bool parallel = context.mode.parallel;
  const size_t threads = parallel ? static_cast<size_t>(std::max(1, context.threads)) : 1;
  model_threads_ = parallel ? arena_slots(threads) : 1;
  model_.resize(model_joints_ * model_threads_);
  stage_ns_.resize(model_threads_);
  const bool layers = any_layers(context.prepared);
  // Room for the largest skeleton now, so that no frame allocates.
  auto reserve = [&](std::vector<LocalPose>& poses, size_t count) {
    poses.resize(count);
    for (LocalPose& pose : poses) {
      pose.translations.reserve(model_joints_);
      pose.rotations.reserve(model_joints_);
      pose.scales.reserve(model_joints_);
    }
  };
  if (!context.crowd->transitions.empty() || layers) reserve(blended_, model_threads_);
  if (layers) {
    reserve(layer_poses_, model_threads_ * kMaxAnimLayers);
    reserve(layer_deltas_, model_threads_ * kMaxAnimLayers);
  }
  if (parallel) {
    threads_ = bench_threads(threads);
    arena_ = threads_->arena.get();
    posed_ = std::make_unique<std::atomic<uint8_t>[]>(threads);  // skin_parts(): fewer states than threads
  }
}

PoseUpdater::~PoseUpdater() = default;

template <typename Body>
void PoseUpdater::for_each_index(std::string_view task, size_t n, const Body& body) {
  if (!arena_) {
    for (size_t i = 0; i < n; ++i) body(i);
    return;
  }
  // One copy per task: a copy is tens of microseconds of work, enough to pay
  // for the task, and fine grains balance copies that are culled.
  Tracer* tracer = context_.tracer;
  arena_->execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1), [&](const tbb::blocked_range<size_t>& range) {
      if (!tracer) {
        for (size_t i = range.begin(); i != range.end(); ++i) body(i);
        return;
      }
      auto start = CategoryClock::Clock::now();
      for (size_t i = range.begin(); i != range.end(); ++i) body(i);
      tracer->span(
          task, "task", start, CategoryClock::Clock::now(), context_.trace_pid,
          {{"first_copy", static_cast<int64_t>(range.begin())}, {"copies", static_cast<int64_t>(range.size())}});
    });
  });
}

uint64_t PoseUpdater::update(std::span<const StateJob> jobs) {
  if (!arena_) {
    uint64_t lookups = 0;
    for (const StateJob& job : jobs) update_state(job, slot_of(job.leader), &lookups, true);
    return lookups;
  }
  std::atomic<uint64_t> total{0};
  if (size_t parts = skin_parts(jobs.size()); parts > 1) {
    // Fewer states than threads (sharing: often one a frame): each state's
    // mesh is skinned in parts, so that every thread has a share. One parallel
    // loop over the parts, so that workers are woken while the first pose is
    // built: the first task of a state to start builds its pose, the others
    // wait for it (for a thread that is running it, never for a queued task).
    for (size_t j = 0; j < jobs.size(); ++j) posed_[j].store(kNotPosed, std::memory_order_relaxed);
    for_each_index("pose+skin part", jobs.size() * parts, [&](size_t t) {
      const size_t j = t / parts;
      uint8_t expected = kNotPosed;
      if (posed_[j].compare_exchange_strong(expected, kPosing, std::memory_order_acq_rel)) {
        uint64_t mine = 0;
        update_state(jobs[j], jobs[j].leader, &mine, false);
        total.fetch_add(mine, std::memory_order_relaxed);
        posed_[j].store(kPosed, std::memory_order_release);
      } else if (posed_[j].load(std::memory_order_acquire) != kPosed) {
        // Meanwhile, the memory this part writes is brought in (storages
        // taken for new states have not been written for many frames).
        prefetch_while(jobs[j].storage, t % parts, parts, posed_[j]);
        while (posed_[j].load(std::memory_order_acquire) != kPosed) std::this_thread::yield();
      }
      const auto since = CategoryClock::Clock::now();
      skin_range(jobs[j].storage, t % parts, parts);
      stage_done(AnimationStage::Skinning, since);
    });
    return total.load();
  }
  for_each_index(skins_in_animations_ ? "pose+skin" : "pose", jobs.size(), [&](size_t j) {
    uint64_t mine = 0;
    update_state(jobs[j], jobs[j].leader, &mine, true);
    // Only string lookups count anything: an add of 0 per copy would still
    // pull the counter's cache line back and forth between the threads.
    if (mine != 0) total.fetch_add(mine, std::memory_order_relaxed);
  });
  return total.load();
}

void PoseUpdater::skin(std::span<const StateJob> jobs) {
  for_each_index("skin", jobs.size(), [&](size_t j) { skin_storage(jobs[j].storage); });
}

AnimationStageTimes PoseUpdater::take_stage_times() {
  AnimationStageTimes times;
  for (StageNanoseconds& thread : stage_ns_)
    for (size_t s = 0; s < kAnimationStageCount; ++s) {
      times.ms[s] += static_cast<double>(thread.ns[s]) * 1e-6;
      thread.ns[s] = 0;
    }
  return times;
}

CategoryClock::Clock::time_point PoseUpdater::stage_done(AnimationStage stage, CategoryClock::Clock::time_point since) {
  const auto now = CategoryClock::Clock::now();
  stage_ns_[worker_index()].ns[static_cast<size_t>(stage)] += (now - since).count();
  if (context_.tracer)
    context_.tracer->span(kAnimationStageNames[static_cast<size_t>(stage)], "animation", since, now,
                          context_.trace_pid);
  return now;
}

size_t PoseUpdater::skin_parts(size_t jobs) const {
  const auto threads = static_cast<size_t>(std::max(1, context_.threads));
  if (!arena_ || jobs == 0 || jobs >= threads || !skins_in_animations_) return 1;
  // Two parts a thread: a worker that wakes late still finds one to take.
  return (4 * threads + jobs - 1) / jobs;
}

size_t PoseUpdater::slot_of(size_t copy) const {
  return context_.mode.pose == PoseStorage::SharedScratch ? crowd_.kind[copy] : copy;
}

void PoseUpdater::update_state(const StateJob& job, size_t slot, uint64_t* lookups, bool skin) {
  auto since = CategoryClock::Clock::now();
  const size_t copy = job.leader;
  const size_t k = crowd_.kind[copy];
  const Character& character = *context_.characters[k];
  const PreparedCharacter& prepared = context_.prepared[k];
  const Skeleton& skeleton = character.skeleton;
  const bool transitions = !store_.actions.empty();
  const size_t action_index = transitions ? store_.actions[copy] : crowd_.action[copy];
  LocalPose& pose = store_.poses[slot];
  // A shared scratch pose still holds the previous copy's joints: start from rest,
  // as the BGE's pose swap copied the armature's own pose in.
  if (context_.mode.pose == PoseStorage::SharedScratch) reset_to_rest(skeleton, &pose);
  if (transitions && store_.cursor_change[copy] != store_.changes[copy]) {
    // A new action since the copy was last posed: its cursors start afresh,
    // and a joint the new action leaves alone starts from rest, not from the
    // old action's last value.
    store_.cursor_change[copy] = store_.changes[copy];
    reset_cursor(character.actions[action_index], &store_.cursors[copy]);
    reset_cursor(character.actions[store_.from_actions[copy]], &store_.from_cursors[copy]);
    reset_to_rest(skeleton, &pose);
    reset_to_rest(skeleton, &store_.from_poses[copy]);
  }
  sample_action(job, slot, action_index, job.time, store_.cursors[copy], pose, lookups);
  since = stage_done(AnimationStage::Sampling, since);
  const BlendLayer alone[] = {{&pose, 1.0f}};
  const LocalPose* shown = transitions               ? fade(job, slot, action_index, pose, lookups, since)
                           : prepared.layers.empty() ? &pose
                                                     : layered(job, slot, action_index, alone, lookups, since);
  std::span<glm::mat4> model = std::span(model_).subspan(worker_index() * model_joints_, prepared.joints);
  run_job(LocalToModelJob{&skeleton, shown, model}, "LocalToModelJob");
  run_job(SkinningMatricesJob{&skeleton, model,
                              std::span(store_.palettes).subspan(store_.joint_offset[job.storage], prepared.joints)},
          "SkinningMatricesJob");
  store_.storage_time[job.storage] = job.time;
  if (transitions) {
    store_.storage_action[job.storage] = static_cast<uint16_t>(action_index);
    store_.storage_weight[job.storage] = job.weight;
  }
  since = stage_done(AnimationStage::LocalToModel, since);
  if (skin && prepared.site == SkinningSite::CpuInAnimations) {
    skin_storage(job.storage);
    stage_done(AnimationStage::Skinning, since);
  }
}

void PoseUpdater::sample_action(const StateJob& job, size_t slot, size_t action_index, float time,
                                SamplingCursor& cursor, LocalPose& pose, uint64_t* lookups) {
  const size_t k = crowd_.kind[job.leader];
  const Action& action = context_.characters[k]->actions[action_index];
  const ActionBindings& bindings = context_.prepared[k].bindings[action_index];
  std::span<const int32_t> targets = bindings.targets;
  if (context_.mode.lookups == Lookups::PerFrameString) {
    std::span<int32_t> scratch = std::span(store_.targets).subspan(store_.slot_channels[slot], action.channels.size());
    size_t count = 0;
    run_job(ResolvePathsJob{&context_.characters[k]->skeleton, &bindings, scratch, &count}, "ResolvePathsJob");
    *lookups += count;
    targets = scratch;
  }
  run_job(SamplingJob{&action, time, targets, &cursor, &pose}, "SamplingJob");
}

const LocalPose* PoseUpdater::fade(const StateJob& job, size_t slot, size_t action_index, const LocalPose& pose,
                                   uint64_t* lookups, CategoryClock::Clock::time_point& since) {
  const size_t copy = job.leader;
  store_.sampled_twice[copy] = 0;
  const float weight = job.weight;
  const PreparedCharacter& prepared = context_.prepared[crowd_.kind[copy]];
  if (!(weight < 1.0f)) {
    if (prepared.layers.empty()) return &pose;
    const BlendLayer alone[] = {{&pose, 1.0f}};
    return layered(job, slot, action_index, alone, lookups, since);
  }
  LocalPose& from = store_.from_poses[copy];
  // Sampled: the old action at its time now, every frame. Frozen: the old
  // action at the change, once per change (the BGE's m_blendinpose).
  const bool frozen = context_.mode.crossfade == Crossfade::Frozen;
  if (!frozen || store_.frozen_change[copy] != store_.changes[copy]) {
    sample_action(job, slot, store_.from_actions[copy], job.from_time, store_.from_cursors[copy], from, lookups);
    store_.frozen_change[copy] = store_.changes[copy];
    store_.sampled_twice[copy] = 1;
    since = stage_done(AnimationStage::Sampling, since);
  }
  // With layers, the fade and the layers are one blend.
  const BlendLayer layers[] = {{&from, 1.0f - weight}, {&pose, weight}};
  if (!prepared.layers.empty()) return layered(job, slot, action_index, layers, lookups, since);
  // Into the thread's scratch, not the copy's pose: a joint the new action
  // leaves alone must keep its rest value after the fade, as it would
  // sampled from rest. The blend writes every joint of its output: the
  // scratch is only sized for this character (within the room reserved).
  LocalPose& blended = blended_[worker_index()];
  const size_t joints = prepared.rest_pose.joint_count();
  blended.translations.resize(joints);
  blended.rotations.resize(joints);
  blended.scales.resize(joints);
  run_job(BlendingJob{layers, &prepared.rest_pose, 0.1f, &blended}, "BlendingJob");
  since = stage_done(AnimationStage::Blending, since);
  return &blended;
}

const LocalPose* PoseUpdater::layered(const StateJob& job, size_t slot, size_t action_index,
                                      std::span<const BlendLayer> own, uint64_t* lookups,
                                      CategoryClock::Clock::time_point& since) {
  const size_t copy = job.leader;
  const size_t k = crowd_.kind[copy];
  const Character& character = *context_.characters[k];
  const PreparedCharacter& prepared = context_.prepared[k];
  const CharacterLayers& layers = prepared.layers;
  const size_t thread = worker_index();
  const std::span<LocalPose> poses = std::span(layer_poses_).subspan(thread * kMaxAnimLayers, layers.layers.size());
  const std::span<LocalPose> deltas = std::span(layer_deltas_).subspan(thread * kMaxAnimLayers, layers.layers.size());
  const Action& own_action = character.actions[action_index];
  for (size_t l = 0; l < layers.layers.size(); ++l) {
    const size_t action = layers.layers[l].action;
    // From rest, as the copy's own pose: a joint the layer's action leaves
    // alone holds its rest value, not another copy's.
    reset_to_rest(character.skeleton, &poses[l]);
    sample_action(job, slot, action, layer_time(own_action, job.time, character.actions[action]),
                  store_.layer_cursors[copy * kMaxAnimLayers + l], poses[l], lookups);
  }
  since = stage_done(AnimationStage::Sampling, since);
  LocalPose& out = blended_[thread];
  const size_t joints = prepared.rest_pose.joint_count();
  out.translations.resize(joints);
  out.rotations.resize(joints);
  out.scales.resize(joints);
  run_job(LayeringJob{&layers, own, poses, deltas, &prepared.rest_pose, &out}, "LayeringJob");
  since = stage_done(AnimationStage::Blending, since);
  return &out;
}

size_t PoseUpdater::worker_index() const {
  if (!arena_) return 0;
  // The arena's slot of the calling thread: unique among the threads in it,
  // below arena_slots() (bench_threads.h), for as long as the task runs.
  const int slot = tbb::this_task_arena::current_thread_index();
  if (slot < 0 || static_cast<size_t>(slot) >= model_threads_)
    throw std::logic_error("a pose update outside the bench's arena");
  return static_cast<size_t>(slot);
}

void PoseUpdater::skin_storage(size_t storage) {
  skin_vertices(storage, 0, vertices_of(storage));
}

void PoseUpdater::skin_range(size_t storage, size_t part, size_t parts) {
  const PreparedCharacter& prepared = context_.prepared[crowd_.kind[storage]];
  if (prepared.site != SkinningSite::CpuInAnimations) return;  // skinned elsewhere (a mixed crowd)
  auto [first, end] = part_of(vertices_of(storage), part, parts);
  skin_vertices(storage, first, end - first);
}

void PoseUpdater::prefetch_while(size_t storage, size_t part, size_t parts, const std::atomic<uint8_t>& posed) const {
  const PreparedCharacter& prepared = context_.prepared[crowd_.kind[storage]];
  if (prepared.site != SkinningSite::CpuInAnimations) return;
  const size_t v = store_.vertex_offset[storage];
  // Positions and normals side by side, 64 vertices at a time (that many
  // floats or codes span whole cache lines), from this part to the mesh's end.
  constexpr size_t kStep = 64;
  const size_t vertices = vertices_of(storage);
  for (size_t first = part_of(vertices, part, parts).first; first < vertices; first += kStep) {
    if (posed.load(std::memory_order_acquire) == kPosed) return;
    const size_t end = std::min(vertices, first + kStep);
    if (store_.packed) {
      prefetch_for_write(&store_.packed_positions[3 * (v + first)], &store_.packed_positions[3 * (v + end)]);
      prefetch_for_write(&store_.packed_normals[v + first], &store_.packed_normals[v + end]);
    } else {
      prefetch_for_write(&store_.positions[v + first], &store_.positions[v + end]);
      prefetch_for_write(&store_.normals[v + first], &store_.normals[v + end]);
    }
  }
}

void PoseUpdater::skin_vertices(size_t storage, size_t first, size_t count) {
  if (count == 0) return;
  const PreparedCharacter& prepared = context_.prepared[crowd_.kind[storage]];
  const size_t v = store_.vertex_offset[storage] + first;
  std::span<const SkinMatrix> palette =
      std::span(store_.palettes).subspan(store_.joint_offset[storage], prepared.joints);
  const SkinningPlan* plan = &prepared.plan_of(level_of(storage));
  if (store_.packed) {
    run_job(PackedSkinningJob{palette, plan, &prepared.quantisation, first, count,
                              std::span(store_.packed_positions).subspan(3 * v, 3 * count),
                              std::span(store_.packed_normals).subspan(v, count)},
            "PackedSkinningJob");
    return;
  }
  run_job(SkinningJob{palette, plan, first, count, std::span(store_.positions).subspan(v, count),
                      std::span(store_.normals).subspan(v, count), store_.stream_output},
          "SkinningJob");
}

}  // namespace crowdprof
