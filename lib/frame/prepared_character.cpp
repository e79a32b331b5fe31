#include "frame/prepared_character.h"

#include "base/errors.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "animation/local_pose.h"
#include "animation/pose.h"
#include "animation/run_job.h"
#include "skinning/bake_deviation.h"

namespace crowdprof {

std::vector<PreparedCharacter> prepare_characters(std::span<const Character* const> characters,
                                                  std::span<const Aabb> boxes, const ModeSwitches& mode,
                                                  size_t max_gpu_joints,
                                                  std::span<const std::vector<AnimLayer>> layers) {
  std::vector<PreparedCharacter> prepared;
  prepared.reserve(characters.size());
  for (size_t k = 0; k < characters.size(); ++k) {
    const Character& character = *characters[k];
    PreparedCharacter p;
    p.joints = character.skeleton.joint_count();
    p.vertices = character.mesh.vertex_count();
    p.site = mode.skinning;
    if (p.site == SkinningSite::Gpu && p.joints > max_gpu_joints) p.site = SkinningSite::CpuInAnimations;
    if (std::string why = build_skinning_plan(character.mesh, p.joints, &p.skinning_plan); !why.empty())
      throw std::runtime_error("skinning plan: " + why);  // the loader checked the same: a bug if reached
    for (const Action& action : character.actions) {
      p.bindings.push_back(bind_action(character.skeleton, action));
      p.max_channels = std::max(p.max_channels, action.channels.size());
    }
    p.posed_on_cpu = !p.bindings.empty() && p.site != SkinningSite::Baked;
    reset_to_rest(character.skeleton, &p.rest_pose);
    if (!layers[k].empty()) {
      // A scene group's layers were checked against its character when read:
      // what fails here is --anim-layer's.
      if (std::string why = resolve_layers(character, p.bindings, layers[k], &p.layers); !why.empty())
        throw UsageError("--anim-layer: " + why);
      if (mode.skinning == SkinningSite::Baked && !p.layers.empty())
        throw UsageError(
            "a scene group's layers: skinning baked draws poses baked per action, which a layer cannot "
            "change: layers run in every mode but baked");
    }
    p.quantisation = position_quantisation(boxes[k].min, boxes[k].max);
    if (mode.mesh_lod) {
      p.mesh_lods = mesh_lods_of(character);
      for (const MeshLod& level : p.mesh_lods) {
        SkinningPlan& plan = p.lod_plans.emplace_back();
        if (std::string why = build_skinning_plan(level.mesh, p.joints, &plan); !why.empty())
          throw std::runtime_error("skinning plan of a mesh level: " + why);  // its joints are the mesh's: a bug
      }
    }
    prepared.push_back(std::move(p));
  }
  return prepared;
}

std::vector<std::vector<AnimLayer>> kind_layers(size_t characters, std::span<const CrowdGroup> groups,
                                                const ModeSwitches& mode) {
  std::vector<std::vector<AnimLayer>> layers(characters, mode.anim_layers);
  for (const CrowdGroup& group : groups)
    if (group.layers && group.character < characters) layers[group.character] = *group.layers;
  return layers;
}

bool any_layers(std::span<const PreparedCharacter> prepared) {
  for (const PreparedCharacter& p : prepared)
    if (!p.layers.empty()) return true;
  return false;
}

std::vector<SkinMatrix> rest_palette(const Character& character) {
  LocalPose rest;
  reset_to_rest(character.skeleton, &rest);
  std::vector<glm::mat4> model(character.skeleton.joint_count());
  run_job(LocalToModelJob{&character.skeleton, &rest, model}, "LocalToModelJob");
  std::vector<SkinMatrix> palette(model.size());
  run_job(SkinningMatricesJob{&character.skeleton, model, palette}, "SkinningMatricesJob");
  return palette;
}

BakeRecord bake_characters(std::span<const Character* const> characters, float rate_hz,
                           std::span<PreparedCharacter> prepared) {
  BakeRecord summary;
  summary.rate_hz = rate_hz;
  for (size_t k = 0; k < characters.size(); ++k) {
    const Character& character = *characters[k];
    PreparedCharacter& p = prepared[k];
    std::vector<std::span<const int32_t>> targets;
    for (const ActionBindings& b : p.bindings) targets.emplace_back(b.targets);
    auto start = std::chrono::steady_clock::now();
    if (!bake_character(character, targets, rate_hz, &p.baked))
      throw std::runtime_error("baking " + character.name + " failed");  // bindings sized by the loader: a bug
    summary.bake_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (character.actions.empty()) {
      p.baked.first_sample = {0};
      p.baked.intervals = {1};
      std::vector<SkinMatrix> rest = rest_palette(character);
      p.baked.matrices = rest;
      p.baked.matrices.insert(p.baked.matrices.end(), rest.begin(), rest.end());
    }
    summary.samples += p.baked.samples();
    BakeDeviation d = measure_bake_deviation(character, targets, p.baked, p.skinning_plan);
    summary.max_deviation = std::max(summary.max_deviation, static_cast<double>(d.model_units));
    summary.max_deviation_fraction =
        std::max(summary.max_deviation_fraction, static_cast<double>(d.fraction_of_height()));
  }
  return summary;
}

std::vector<CharacterView> character_views(std::span<const PreparedCharacter> prepared) {
  std::vector<CharacterView> views;
  for (const PreparedCharacter& p : prepared)
    views.push_back({p.site, p.joints, p.vertices, p.baked.joints ? &p.baked : nullptr, p.quantisation, p.mesh_lods});
  return views;
}

}  // namespace crowdprof
