// What a run is checked by, beside its timings: how far the drawn vertices
// stray from exact times (sharing, LOD, budget, baking) and the digest of the
// last frame's work. Split from crowd_bench.cpp, which runs the frames.
#include "frame/crowd_bench.h"
#include "animation/run_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "animation/exact_palette.h"
#include "animation/pose.h"
#include "asset/mesh_lod.h"
#include "asset/standing.h"
#include "frame/bench_threads.h"
#include "scene/screen_size.h"
#include "skinning/skinning.h"

namespace crowdprof {

std::span<const SkinMatrix> CrowdBench::exact_palette(size_t copy, float time, ExactPalette& scratch) const {
  const Character& character = character_of(copy);
  const PreparedCharacter& kind = prepared_[crowd_.kind[copy]];
  if (character.actions.empty()) return scratch.at(character.skeleton, nullptr, {}, time);
  const ExactLayers layers{&kind.layers, character.actions, kind.bindings, &kind.rest_pose};
  if (!transitions_) {
    const size_t a = crowd_.action[copy];
    return scratch.at(character.skeleton, &character.actions[a], kind.bindings[a].targets, time, layers);
  }
  const size_t a = store_->actions[copy], from = store_->from_actions[copy];
  if (!(store_->weights[copy] < 1.0f))
    return scratch.at(character.skeleton, &character.actions[a], kind.bindings[a].targets, time, layers);
  return scratch.fading(character.skeleton, kind.rest_pose, character.actions[from], kind.bindings[from].targets,
                        store_->from_times[copy], character.actions[a], kind.bindings[a].targets, time,
                        store_->weights[copy], layers);
}

AnimationRecord CrowdBench::measure_animation() const {
  AnimationRecord fidelity;
  const UpdateSchedule& plan = schedule();
  fidelity.copies_by_rate.assign(plan.copies_by_rate.begin(), plan.copies_by_rate.end());
  fidelity.longest_gap_frames = plan.longest_gap;
  fidelity.budget_demotions = plan.demotions;
  std::vector<float> heights;
  for (const Character* character : characters_) heights.push_back(standing_of(*character).height);
  ExactPalette reference;
  std::vector<glm::vec3> drawn, drawn_normals, exact, exact_normals;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!store_->visible[i] || !planner_->poses(i, store_->visible)) continue;
    ++fidelity.copies_checked;
    // Drawn at its exact time (same action: a copy's storage holds its own action).
    const size_t storage = storage_of(i);
    const bool same_state = store_->storage_time[storage] == store_->times[i] &&
                            (!transitions_ || (store_->storage_action[storage] == store_->actions[i] &&
                                               store_->storage_weight[storage] == store_->weights[i]));
    if (same_state) continue;
    ++fidelity.copies_deviating;
    const PreparedCharacter& kind = prepared_[crowd_.kind[i]];
    const std::span<const SkinMatrix> palette = exact_palette(i, store_->times[i], reference);
    for (auto* v : {&drawn, &drawn_normals, &exact, &exact_normals}) v->resize(kind.vertices);
    // Both skinned here, so that a copy skinned on the GPU is measured too.
    run_job(SkinningJob{skinning_matrices(i), &kind.skinning_plan, 0, kind.vertices, drawn, drawn_normals},
            "SkinningJob");
    run_job(SkinningJob{palette, &kind.skinning_plan, 0, kind.vertices, exact, exact_normals}, "SkinningJob");
    double worst = 0;
    for (size_t v = 0; v < kind.vertices; ++v)
      worst = std::max(worst, static_cast<double>(glm::distance(drawn[v], exact[v])));
    fidelity.max_deviation = std::max(fidelity.max_deviation, worst);
    double height = heights[crowd_.kind[i]];
    if (height > 0)
      fidelity.deviation_fraction_of_height = std::max(fidelity.deviation_fraction_of_height, worst / height);
  }
  return fidelity;
}

namespace {

// Copies (or copy-poses) an end-of-run check may skin: `limit`, fewer for big
// meshes, so that it skins at most `vertex_budget` vertices whatever the mesh.
size_t checked_copies(std::span<const Character* const> characters, size_t limit, size_t vertex_budget) {
  size_t largest = 1;
  for (const Character* character : characters) largest = std::max(largest, character->mesh.vertex_count());
  return std::max<size_t>(1, std::min(limit, vertex_budget / largest));
}

// The samples of a baked action whose sample 0 is `first_sample`.
std::span<const SkinMatrix> baked_samples_of(const BakedCharacter& baked, uint32_t first_sample, uint32_t intervals) {
  return std::span(baked.matrices).subspan(size_t{first_sample} * baked.joints, (size_t{intervals} + 1) * baked.joints);
}

// One copy's share of the drawn error.
struct CopyError {
  bool checked = false, deviating = false;
  uint64_t vertices = 0;
  double max = 0, sum_squares = 0, height = 0, px_per_unit = 0, level_error = 0;
};

struct ErrorScratch {
  ExactPalette reference;
  std::vector<SkinMatrix> drawn, from;
  std::vector<glm::vec3> drawn_positions, exact_positions, normals;
};

}  // namespace

DrawnErrorRecord CrowdBench::measure_drawn_error(int screen_height_px, size_t max_copies) const {
  DrawnErrorRecord error;
  if (frame_ == 0) return error;
  // The last frame's exact clock (frustum gpu keeps no times on the CPU).
  const double seconds = static_cast<double>(frame_ - 1) / config_.fps;
  const glm::mat4 view_projection = camera_.view_projection();
  std::vector<size_t> on_screen;
  for (size_t i = 0; i < crowd_.size(); ++i)
    if (intersects(frustum_, crowd_.world_boxes[i])) on_screen.push_back(i);
  max_copies = checked_copies(characters_, max_copies, 200'000'000);  // each copy skinned twice
  error.copy_stride = std::max<size_t>(1, (on_screen.size() + max_copies - 1) / std::max<size_t>(1, max_copies));
  std::vector<CopyError> copies((on_screen.size() + error.copy_stride - 1) / error.copy_stride);
  std::vector<float> heights;
  for (const Character* character : characters_) heights.push_back(standing_of(*character).height);
  tbb::enumerable_thread_specific<ErrorScratch> scratches;
  auto measure = [&](const tbb::blocked_range<size_t>& range) {
    ErrorScratch& s = scratches.local();
    for (size_t n = range.begin(); n != range.end(); ++n) {
      const size_t i = on_screen[n * error.copy_stride];
      const size_t k = crowd_.kind[i];
      const PreparedCharacter& kind = prepared_[k];
      if (kind.vertices == 0) continue;
      CopyError& e = copies[n];
      e.checked = true;
      const float time = transitions_ ? store_->times[i] : copy_time(i, seconds);
      const std::span<const SkinMatrix> exact = exact_palette(i, time, s.reference);
      // The palette drawn: the baked blend the shader makes, or the pose storage's.
      std::span<const SkinMatrix> drawn = skinning_matrices(i);
      if (kind.site == SkinningSite::Baked) {
        const BakedInstance instance = baked_instance(i, action_now(i), time);
        s.drawn.resize(kind.joints);
        const BakedPaletteJob now{baked_samples_of(kind.baked, instance.first_sample, instance.intervals), kind.joints,
                                  instance.position, s.drawn};
        // A fading copy: as the shader mixes its record with the action it leaves.
        if (const BakedFade fade = baked_fade(i); fade.fading()) {
          s.from.resize(kind.joints);
          run_job(BakedFadeJob{now,
                               {baked_samples_of(kind.baked, fade.first_sample, fade.intervals), kind.joints,
                                fade.position, s.from},
                               fade.weight},
                  "BakedFadeJob");
        } else {
          run_job(now, "BakedPaletteJob");
        }
        drawn = s.drawn;
      }
      const size_t level = level_of(i);
      const size_t vertices = kind.vertices_of(level);
      for (auto* v : {&s.drawn_positions, &s.exact_positions, &s.normals}) v->resize(vertices);
      run_job(SkinningJob{drawn, &kind.plan_of(level), 0, vertices, s.drawn_positions, s.normals}, "SkinningJob");
      run_job(SkinningJob{exact, &kind.plan_of(level), 0, vertices, s.exact_positions, s.normals}, "SkinningJob");
      e.level_error = level == 0 ? 0.0 : static_cast<double>(kind.mesh_lods[level - 1].error);
      e.vertices = vertices;
      double pose_max = 0;
      for (size_t v = 0; v < vertices; ++v) {
        const double d = glm::distance(s.drawn_positions[v], s.exact_positions[v]);
        pose_max = std::max(pose_max, d);
        e.sum_squares += (d + e.level_error) * (d + e.level_error);
      }
      e.max = pose_max + e.level_error;
      e.deviating = e.max > 0;
      e.height = heights[k];
      const Aabb& box = crowd_.world_boxes[i];
      const double box_height = box.max.y - box.min.y;
      e.px_per_unit = box_height > 0 ? screen_height_fraction(view_projection, box) *
                                           static_cast<double>(screen_height_px) / box_height
                                     : 0.0;
    }
  };
  auto run = [&] { tbb::parallel_for(tbb::blocked_range<size_t>(0, copies.size(), 8), measure); };
  bench_threads(config_.mode.parallel ? config_.threads : 1)->arena->execute(run);
  // Summed in copy order: the same figures on any thread count.
  double sum_squares = 0, sum_fraction = 0, sum_px = 0;
  for (const CopyError& e : copies) {
    if (!e.checked) continue;
    ++error.copies_checked;
    error.copies_deviating += e.deviating;
    error.vertices += e.vertices;
    error.max = std::max(error.max, e.max);
    error.mesh_max = std::max(error.mesh_max, e.level_error);
    error.max_px = std::max(error.max_px, e.max * e.px_per_unit);
    sum_squares += e.sum_squares;
    sum_px += e.sum_squares * e.px_per_unit * e.px_per_unit;
    if (e.height > 0) {
      error.max_fraction = std::max(error.max_fraction, e.max / e.height);
      sum_fraction += e.sum_squares / (e.height * e.height);
    }
  }
  if (error.vertices) {
    const double n = static_cast<double>(error.vertices);
    error.rms = std::sqrt(sum_squares / n);
    error.rms_fraction = std::sqrt(sum_fraction / n);
    error.rms_px = std::sqrt(sum_px / n);
  }
  return error;
}

MeshLodRecord CrowdBench::mesh_lod_fidelity(int screen_height_px) const {
  MeshLodRecord record;
  // The levels some character has: a mesh the simplifier could not reduce
  // (the Fox: no vertex shared between triangles) records its full mesh alone.
  size_t used = 1;
  for (const PreparedCharacter& p : prepared_) used = std::max(used, std::min<size_t>(p.levels(), kMeshLevels));
  record.levels.resize(mesh_level_.empty() ? kMeshLevels : used);
  std::vector<MeshLevelRecord>& levels = record.levels;
  if (mesh_level_.empty()) return record;
  // Each level's error, the worst character's, whether or not a copy is at it.
  for (size_t k = 0; k < characters_.size(); ++k) {
    const float height = standing_of(*characters_[k]).height;
    for (size_t level = 1; level < prepared_[k].levels() && level < kMeshLevels; ++level) {
      const double error = prepared_[k].mesh_lods[level - 1].error;
      levels[level].error = std::max(levels[level].error, error);
      if (height > 0) levels[level].error_fraction = std::max(levels[level].error_fraction, error / height);
    }
  }
  const glm::mat4 view_projection = camera_.view_projection();
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!store_->visible[i]) continue;
    const size_t k = crowd_.kind[i], level = mesh_level_[i];
    MeshLevelRecord& f = levels[level];
    ++f.copies;
    if (level == 0) continue;
    const double error = prepared_[k].mesh_lods[level - 1].error;
    // Pixels a model unit spans at this copy's size: its box's projected share
    // of the screen's height over the box's own height.
    const Aabb& box = crowd_.world_boxes[i];
    const double box_height = box.max.y - box.min.y;
    if (box_height > 0)
      f.error_px =
          std::max(f.error_px, error * screen_height_fraction(view_projection, box) * screen_height_px / box_height);
  }
  return record;
}

CullingAudit CrowdBench::audit_culling(size_t max_copy_frames) const {
  const auto start = std::chrono::steady_clock::now();
  const size_t n = crowd_.size();
  if (n == 0) return {};
  // 40,000 poses of the humanoid are 2e8 vertices: no more for a bigger mesh.
  max_copy_frames = checked_copies(characters_, max_copy_frames, 200'000'000);
  const size_t stride = (n + max_copy_frames - 1) / max_copy_frames;
  const size_t audited = (n + stride - 1) / stride;
  const size_t frames = std::clamp<size_t>(max_copy_frames / audited, 1, 16);
  // Poses spread over the longest action, so that each copy's whole action is
  // seen (a run of a few frames covers a fraction of a second of it).
  double span = 0;
  for (const Character* character : characters_)
    for (const Action& action : character->actions) span = std::max(span, static_cast<double>(action.duration()));
  CullingAuditor auditor(characters_, crowd_, frustum_, stride);
  std::shared_ptr<BenchThreads> threads = bench_threads(config_.mode.parallel ? config_.threads : 1);
  std::vector<float> times(n, 0.0f);
  for (size_t f = 0; f < frames; ++f) {
    const double seconds = span * static_cast<double>(f) / static_cast<double>(frames);
    for (size_t i = 0; i < n; ++i) times[i] = copy_time(i, seconds);
    auditor.add_frame(times, threads->arena.get());
  }
  CullingAudit audit = auditor.audit();
  audit.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return audit;
}

namespace {
void fnv1a(uint64_t& hash, const void* data, size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ull;
}
}  // namespace

std::string CrowdBench::digest() const {
  uint64_t hash = 0xcbf29ce484222325ull;
  // frustum gpu keeps no times on the CPU: the last frame's, as the cull pass made them.
  const double last_seconds = frame_ > 0 ? static_cast<double>(frame_ - 1) / config_.fps : 0.0;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!store_->visible[i]) continue;
    auto palette = skinning_matrices(i);
    fnv1a(hash, palette.data(), palette.size_bytes());
    // The mesh it draws, when not the full one (no LOD level digests as LOD off).
    if (!mesh_level_.empty() && mesh_level_[i] != 0) fnv1a(hash, &mesh_level_[i], 1);
    if (prepared_[crowd_.kind[i]].site == SkinningSite::Baked) {
      // Never posed on the CPU: what the GPU is told to draw is the copy's place among its samples.
      BakedInstance instance =
          baked_instance(i, action_now(i), gpu_visible_.empty() ? store_->times[i] : copy_time(i, last_seconds));
      fnv1a(hash, &instance, sizeof instance);
      if (transitions_) {
        const BakedFade fade = baked_fade(i);
        fnv1a(hash, &fade, sizeof fade);
      }
    } else if (!gpu_skinned_copy(i) && packed_vertices()) {
      fnv1a(hash, packed_positions(i).data(), packed_positions(i).size_bytes());
      fnv1a(hash, packed_normals(i).data(), packed_normals(i).size_bytes());
    } else if (!gpu_skinned_copy(i)) {
      fnv1a(hash, skinned_positions(i).data(), skinned_positions(i).size_bytes());
      fnv1a(hash, skinned_normals(i).data(), skinned_normals(i).size_bytes());
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return hex;
}

}  // namespace crowdprof
