#include "frame/crowd_bench.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "base/errors.h"
#include "measuring/trace.h"
#include "scene/screen_size.h"
#include "scene/shadow_cascades.h"

namespace crowdprof {

SettingText why_cannot_run(const BenchConfig& config) {
  SettingText conflict = conflicts(config.mode);
  if (!conflict.empty()) return conflict;
  if (skins_on_gpu(config.mode.skinning) && !config.renderer)
    return "skinning on the GPU (skinning " + std::string(to_string(config.mode.skinning)) +
           ") needs a GL backend: {backend} auto, egl or osmesa";
  if (config.mode.passes > 1 && !config.renderer)
    return "{passes} " + std::to_string(config.mode.passes) +
           " draws the crowd several times a frame, which needs a GL backend: {backend} auto, egl or osmesa";
  if (config.mode.skinning == SkinningSite::Baked && !(config.bake_rate_hz > 0.0f && config.bake_rate_hz <= 10000.0f))
    return "{bake_rate} " + std::to_string(config.bake_rate_hz) +
           ": expected more than 0 and at most 10000 samples per second";
  return {};
}

CrowdBench::CrowdBench(const Character& character, const BenchConfig& config)
    : CrowdBench(std::span<const Character* const>(std::array<const Character*, 1>{&character}), config) {}

CrowdBench::CrowdBench(std::span<const Character* const> characters, const BenchConfig& config)
    : characters_(characters.begin(), characters.end()), config_(config) {
  if (SettingText why = why_cannot_run(config); !why.empty()) throw SettingsUsageError(why);
  if (config.renderer) config.renderer->require(config.mode);
  if (characters_.empty()) throw UsageError("a crowd needs at least one character");
  for (const CrowdGroup& group : crowd_groups(config.crowd)) {
    if (group.character >= characters_.size()) throw UsageError("a crowd group names a character that is not there");
    if (characters_[group.character]->actions.empty() && group.actions != ActionChoice::Shared)
      throw UsageError("random actions need a character with actions");
  }
  const ModeSwitches& mode = config.mode;
  CrowdOptions crowd = config.crowd;
  crowd.transitions = {mode.transitions_s, mode.blend_in_s};
  crowd_ = make_crowd(characters_, crowd);
  if (!crowd_.transitions.empty() && mode.frustum == FrustumTest::Gpu)
    throw SettingsUsageError(
        "the scene's groups change action (transitions), and {frustum} gpu's cull pass times every copy from a "
        "clock fixed at load: they need {frustum} cpu (skinning baked fades there)");
  camera_ = make_camera(config.camera, crowd_.crowd_box, config.aspect, config.lens);
  frustum_ = frustum_of(camera_.view_projection());
  // The immutable data first, then the arrays each copy writes, then the jobs.
  prepared_ = prepare_characters(characters_, crowd_.character_boxes, mode,
                                 config.renderer ? config.renderer->max_gpu_joints(mode) : 0,
                                 kind_layers(characters_.size(), config.crowd.groups, mode));
  character_counters_.resize(characters_.size());
  if (mode.mesh_lod) choose_mesh_levels();
  store_ = std::make_unique<CopyStore>(characters_, prepared_, crowd_, mode, mesh_level_);
  if (!crowd_.transitions.empty())
    transitions_ = std::make_unique<TransitionSchedule>(characters_, crowd_, config.crowd.seed);
  std::vector<uint8_t> posed_on_cpu;
  for (const PreparedCharacter& p : prepared_) posed_on_cpu.push_back(p.posed_on_cpu);
  planner_ =
      std::make_unique<UpdatePlanner>(characters_, crowd_, camera_.view_projection(), mode, std::move(posed_on_cpu));
  poser_ =
      std::make_unique<PoseUpdater>(PoseUpdateContext{characters_, prepared_, &crowd_, store_.get(), mode,
                                                      config.threads, config.tracer, config.trace_pid, mesh_level_});
  if (mode.skinning == SkinningSite::Baked) {
    bake_summary_ = bake_characters(characters_, config.bake_rate_hz, prepared_);
    baked_instances_.resize(crowd_.size());
    if (transitions_) baked_fades_.resize(crowd_.size());
  }
  copies_of_character_.assign(characters_.size(), 0);
  for (uint16_t k : crowd_.kind) ++copies_of_character_[k];
  if (mode.frustum == FrustumTest::Gpu) {
    baked_clocks_.resize(crowd_.size());
    for (size_t i = 0; i < crowd_.size(); ++i) baked_clocks_[i] = baked_clock(i);
    gpu_visible_.assign(characters_.size() * kMeshLevels, 0);
  }
  character_views_ = character_views(prepared_);
  view_.mode = mode;
  view_.view_projection = camera_.view_projection();
  shadow_cameras_ = shadow_cascades(camera_, crowd_.crowd_box, kLightDirection, mode.passes > 2 ? mode.passes - 2 : 0);
  view_.shadow_view_projections = shadow_cameras_;
  view_.characters = character_views_;
  view_.kind = crowd_.kind;
  view_.world = crowd_.world;
  view_.visible = store_->visible;
  view_.shown = planner_->shown();
  view_.baked = baked_instances_;
  view_.baked_fades = baked_fades_;
  view_.world_boxes = crowd_.world_boxes;
  view_.baked_clocks = baked_clocks_;
  view_.mesh_level = mesh_level_;
  view_.joint_offset = store_->joint_offset;
  view_.vertex_offset = store_->vertex_offset;
  view_.palettes = store_->palettes;
  view_.positions = store_->positions;
  view_.normals = store_->normals;
  view_.packed_positions = store_->packed_positions;
  view_.packed_normals = store_->packed_normals;
  // The scenegraph of "frame -1": the first frame's animation culling needs it.
  Counters unused;
  update_scenegraph(unused);
  // Copies stand still and the camera too: who is posed, and how big, is
  // known now and for good.
  planner_->start_budget(store_->visible);
  if (config.renderer) {
    config.renderer->prepare(view_);
    animation_gpu_bytes_ = config.renderer->animation_gpu_bytes();
  }
  loaded_ = true;
}

CrowdBench::~CrowdBench() = default;

void CrowdBench::choose_mesh_levels() {
  const MeshLodThresholds& at = config_.mode.mesh_lod_at;
  const float thresholds[3] = {at.level_1, at.level_2, at.level_3};
  mesh_level_.assign(crowd_.size(), 0);
  const glm::mat4 view_projection = camera_.view_projection();
  for (size_t i = 0; i < crowd_.size(); ++i) {
    const size_t levels = prepared_[crowd_.kind[i]].levels();
    // Off screen (skinned all the same with culling off): the coarsest level.
    if (!intersects(frustum_, crowd_.world_boxes[i])) {
      mesh_level_[i] = static_cast<uint8_t>(std::min(levels, kMeshLevels) - 1);
      continue;
    }
    mesh_level_[i] = mesh_level_for(screen_height_fraction(view_projection, crowd_.world_boxes[i]), 0, thresholds,
                                    kMeshLodHysteresis, levels);
  }
}

uint64_t CrowdBench::triangles_of(size_t kind, size_t level) const {
  const PreparedCharacter& p = prepared_[kind];
  return level == 0 ? characters_[kind]->mesh.triangle_count() : p.mesh_lods[level - 1].mesh.triangle_count();
}

BakedInstance CrowdBench::baked_instance(size_t copy, size_t action, float time) const {
  const PreparedCharacter& p = prepared_[crowd_.kind[copy]];
  BakedInstance instance;
  if (!p.baked.joints) return instance;
  const Character& character = character_of(copy);
  const size_t a = character.actions.empty() ? 0 : action;
  instance.first_sample = static_cast<uint32_t>(p.baked.first_sample[a]);
  instance.intervals = static_cast<uint32_t>(p.baked.intervals[a]);
  if (!character.actions.empty()) instance.position = baked_position(character.actions[a], instance.intervals, time);
  return instance;
}

BakedFade CrowdBench::baked_fade(size_t copy) const {
  if (!transitions_ || !(store_->weights[copy] < 1.0f)) return {};
  const BakedInstance from = baked_instance(copy, store_->from_actions[copy], store_->from_times[copy]);
  return {from.first_sample, from.intervals, from.position, 1.0f - store_->weights[copy]};
}

BakedClock CrowdBench::baked_clock(size_t copy) const {
  const PreparedCharacter& p = prepared_[crowd_.kind[copy]];
  BakedClock clock;
  if (!p.baked.joints) return clock;
  const Character& character = character_of(copy);
  const size_t a = character.actions.empty() ? 0 : crowd_.action[copy];
  clock.first_sample = static_cast<uint32_t>(p.baked.first_sample[a]);
  clock.intervals = static_cast<uint32_t>(p.baked.intervals[a]);
  if (character.actions.empty()) return clock;
  const Action& action = character.actions[a];
  clock.phase = crowd_.phase[copy];
  clock.start = action.start;
  clock.end = action.end;
  clock.duration = action.duration() > 0 ? action.duration() : 0.0f;
  return clock;
}

void CrowdBench::place_baked_instances() {
  for (size_t i = 0; i < crowd_.size(); ++i) {
    if (!store_->visible[i]) continue;
    baked_instances_[i] = baked_instance(i, action_now(i), store_->times[i]);
    if (transitions_) baked_fades_[i] = baked_fade(i);
  }
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
  const uint64_t switches_before = planner_->schedule().rate_switches;
  update_poses(counters);
  record.animation_stages = poser_->take_stage_times();
  record.rate_switches = planner_->schedule().rate_switches - switches_before;
  enter(Category::Scenegraph);
  update_scenegraph(counters);
  enter(Category::Rasterizer);
  if (config_.mode.skinning == SkinningSite::CpuInRasterizer) poser_->skin(planner_->jobs());
  if (config_.renderer) {
    if (!baked_instances_.empty() && gpu_visible_.empty()) place_baked_instances();
    view_.frame = frame_;
    view_.seconds = static_cast<double>(frame_) / config_.fps;
    config_.renderer->draw(view_, counters);
  }
  enter(Category::GpuLatency);  // without a GL backend, nothing to wait for
  if (config_.renderer) config_.renderer->finish();
  enter(Category::Overhead);
  count_work(counters);
  // Timer queries of earlier frames that have finished; never waits for one.
  gpu_time_count_ = config_.renderer ? config_.renderer->take_gpu_times(&view_, frame_, gpu_times_, false) : 0;
  ++frame_;
  // Between frames (reports, progress) is outside the engine's frame.
  enter(Category::Outside);
  if (config_.tracer)
    config_.tracer->span("frame", "frame", frame_start_, stage_start_, config_.trace_pid,
                         {{"frame", static_cast<int64_t>(frame_ - 1)}});
  record.cpu_ms = process_cpu_ms() - cpu_start;
  record.times = clock_.end_frame();
  last_animations_ms_ = record.times.ms[static_cast<size_t>(Category::Animations)];
  return record;
}

void CrowdBench::collect_gpu_times() {
  gpu_time_count_ = config_.renderer ? config_.renderer->take_gpu_times(&view_, frame_, gpu_times_, true) : 0;
}

std::string CrowdBench::pipeline_statistics_missing() const {
  return config_.renderer ? config_.renderer->pipeline_statistics_missing() : "no GL backend (--backend none)";
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

float CrowdBench::copy_time(size_t copy, double seconds) const {
  const Character& character = character_of(copy);
  if (character.actions.empty()) return 0.0f;

  const Action& action = character.actions[crowd_.action[copy]];
  double duration = action.duration();
  double local = duration > 0 ? std::fmod(static_cast<double>(crowd_.phase[copy]) + seconds, duration) : 0.0;
  return action.start + static_cast<float>(local);
}

void CrowdBench::update_logic() {
  if (!gpu_visible_.empty()) return;  // frustum gpu: the cull pass computes each copy's time (cull.comp)
  const double t = static_cast<double>(frame_) / config_.fps;
  if (transitions_) return update_transitions(t);
  for (size_t i = 0; i < crowd_.size(); ++i)
    if (!character_of(i).actions.empty()) store_->times[i] = copy_time(i, t);
}

void CrowdBench::update_transitions(double t) {
  transitions_->advance(t);
  CopyStore& s = *store_;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    const std::vector<Action>& actions = character_of(i).actions;
    if (actions.empty()) continue;
    const CopyAction& c = (*transitions_)[i];
    s.actions[i] = c.now.action;
    s.times[i] = c.now.local_time(actions[c.now.action], t);
    s.changes[i] = c.changes;
    s.weights[i] = c.weight;
    s.from_actions[i] = c.before.action;
    // Frozen: the old action where the change found it; sampled: where it is now.
    const double from_at = config_.mode.crossfade == Crossfade::Frozen ? c.changed_at : t;
    s.from_times[i] = c.before.local_time(actions[c.before.action], from_at);
  }
}

void CrowdBench::update_poses(Counters& counters) {
  // For tests of the budget: a replayed Animations time makes its choices reproducible.
  const std::vector<double>& replay = config_.replay_animations_ms;
  const double measured = replay.empty() || frame_ == 0 ? last_animations_ms_ : replay[(frame_ - 1) % replay.size()];
  std::span<const StateJob> jobs = planner_->plan({frame_, store_->times, store_->visible, measured, store_->actions,
                                                   store_->from_actions, store_->weights, store_->from_times},
                                                  counters);
  counters.channel_lookups = poser_->update(jobs);
}

void CrowdBench::update_scenegraph(Counters& counters) {
  // frustum gpu: the GPU tests the copies (counted after the frame, count_work);
  // the test at load (frame -1) still runs, for the planner's set-up.
  if (!gpu_visible_.empty() && loaded_) return;
  uint64_t visible = 0;
  for (size_t i = 0; i < crowd_.size(); ++i) {
    store_->visible[i] = intersects(frustum_, crowd_.world_boxes[i]) ? 1 : 0;
    visible += store_->visible[i];
  }
  counters.copies_visible = visible;
}

void CrowdBench::count_gpu_culled_work(Counters& counters) {
  // The GPU's own counts; a GL that could not say leaves them all off screen.
  if (!config_.renderer || !config_.renderer->gpu_visible_counts(view_, gpu_visible_))
    throw std::runtime_error("the GPU's cull pass gave no count of the copies it found on screen");
  uint64_t visible = 0, culled = 0;
  for (size_t k = 0; k < characters_.size(); ++k) {
    Counters& c = character_counters_[k];
    c = Counters{};
    // Per mesh level (level 0 alone without mesh LOD): copies, and the vertices
    // the GPU skins and the triangles it draws for them.
    for (size_t level = 0; level < kMeshLevels; ++level) {
      const uint64_t copies = gpu_visible_[k * kMeshLevels + level];
      if (copies == 0) continue;
      // A level the character lacks was never appended to: a pass that says so is broken.
      if (level >= prepared_[k].levels())
        throw std::runtime_error("the GPU's cull pass drew a mesh level the character lacks");
      c.*kLodCopies[level] = copies;
      c.*kLodVertices[level] = copies * prepared_[k].vertices_of(level);
      c.*kLodTriangles[level] = copies * triangles_of(k, level);
      c.vertices_drawn += copies * prepared_[k].vertices_of(level);
      c.copies_visible += copies;
    }
    c.copies_visible = std::min(c.copies_visible, copies_of_character_[k]);
    const bool moves = !prepared_[k].bindings.empty();
    c.copies_culled = moves && config_.mode.animation_culling ? copies_of_character_[k] - c.copies_visible : 0;
    visible += c.copies_visible;
    culled += c.copies_culled;
  }
  counters.copies_visible = visible;
  counters.copies_culled = culled;
  add_lod_counters(counters);
}

void CrowdBench::add_lod_counters(Counters& counters) const {
  for (const Counters& c : character_counters_)
    for (size_t level = 0; level < kMeshLevels; ++level) {
      counters.*kLodCopies[level] += c.*kLodCopies[level];
      counters.*kLodVertices[level] += c.*kLodVertices[level];
      counters.*kLodTriangles[level] += c.*kLodTriangles[level];
    }
  for (const Counters& c : character_counters_) counters.vertices_drawn += c.vertices_drawn;
}

void CrowdBench::count_work(Counters& counters) {
  if (!gpu_visible_.empty()) return count_gpu_culled_work(counters);
  for (Counters& c : character_counters_) c = Counters{};
  for (size_t i = 0; i < crowd_.size(); ++i) {
    Counters& c = character_counters_[crowd_.kind[i]];
    c.copies_visible += store_->visible[i];
    // A character without actions stands in its rest pose: never posed, never culled.
    const bool moves = !prepared_[crowd_.kind[i]].bindings.empty();
    const bool updated = planner_->updated(i);
    c.copies_culled += moves && !animates(i);
    c.copies_updated += updated;
    c.copies_held += planner_->poses(i, store_->visible) && !updated;
    if (updated) ++(c.*kUpdatesByShift[planner_->shift(i)]);
    if (store_->visible[i]) {
      const size_t k = crowd_.kind[i], level = level_of(i);
      ++(c.*kLodCopies[level]);
      c.*kLodTriangles[level] += triangles_of(k, level);
      c.vertices_drawn += prepared_[k].vertices_of(level);
      // The GPU skins every copy it draws, once a frame.
      if (skins_on_gpu(prepared_[k].site)) c.*kLodVertices[level] += prepared_[k].vertices_of(level);
    }
  }
  // An evaluation is one pose sampled and rebuilt, and one mesh skinned on the CPU.
  for (const StateJob& job : planner_->jobs()) {
    const size_t k = crowd_.kind[job.leader];
    Counters& c = character_counters_[k];
    ++c.poses_updated;
    ++c.actions_sampled;
    const bool fading = transitions_ && job.weight < 1.0f;
    if (fading) {
      ++c.fades;
      c.actions_sampled += store_->sampled_twice[job.leader];
    }
    // Layers: their actions sampled, and one blend whether or not it fades.
    c.actions_sampled += prepared_[k].layers.layers.size();
    c.layers += prepared_[k].layers.layers.size();
    if (fading || !prepared_[k].layers.empty()) c.joints_blended += prepared_[k].joints;
    if (skins_on_gpu(prepared_[k].site)) continue;
    const size_t level = level_of(job.storage), vertices = prepared_[k].vertices_of(level);
    c.vertices_skinned += vertices;
    c.*kLodVertices[level] += vertices;
  }
  uint64_t posed = 0, culled = 0, skinned = 0, fallback = 0;
  for (size_t k = 0; k < prepared_.size(); ++k) {
    Counters& c = character_counters_[k];
    if (prepared_[k].site != SkinningSite::Gpu && config_.mode.skinning == SkinningSite::Gpu)
      c.copies_fallback = c.poses_updated;
    posed += c.poses_updated;
    culled += c.copies_culled;
    skinned += c.vertices_skinned;
    fallback += c.copies_fallback;
    counters.actions_sampled += c.actions_sampled;
    counters.fades += c.fades;
    counters.layers += c.layers;
    counters.joints_blended += c.joints_blended;
  }
  counters.poses_updated = posed;
  counters.copies_culled = culled;
  counters.vertices_skinned = skinned;
  counters.copies_fallback = fallback;
  add_lod_counters(counters);
}

}  // namespace crowdprof
