#include "animation/layering.h"

#include <algorithm>
#include <cmath>

#include "animation/joint_mask.h"
#include "animation/run_job.h"
#include "animation/sampling.h"

namespace crowdprof {

std::string resolve_layers(const Character& character, std::span<const ActionBindings> bindings,
                           std::span<const AnimLayer> specs, CharacterLayers* out) {
  CharacterLayers resolved;
  if (specs.size() > kMaxAnimLayers) return "at most " + std::to_string(kMaxAnimLayers) + " layers";
  const Skeleton& skeleton = character.skeleton;
  for (const AnimLayer& spec : specs) {
    auto found = std::find_if(character.actions.begin(), character.actions.end(),
                              [&](const Action& a) { return a.name == spec.action; });
    if (found == character.actions.end()) {
      std::string names;
      for (const Action& a : character.actions) names += (names.empty() ? "" : ", ") + a.name;
      return "no action '" + spec.action + "' in " + character.name +
             (names.empty() ? " (it has none)" : " (its actions are " + names + ")");
    }
    CharacterLayers::Layer layer;
    layer.action = static_cast<size_t>(found - character.actions.begin());
    layer.weight = static_cast<float>(spec.weight);
    layer.additive = spec.blend == LayerBlend::Add;
    if (std::string problem = joint_mask(skeleton, spec.mask, spec.falloff, &layer.mask); !problem.empty())
      return problem + " in " + character.name;
    if (!(layer.weight > 0.0f)) continue;
    if (layer.additive) {
      SamplingCursor cursor;
      reset_to_rest(skeleton, &layer.reference);
      reset_cursor(*found, &cursor);
      run_job(SamplingJob{&*found, found->start, bindings[layer.action].targets, &cursor, &layer.reference},
              "SamplingJob");
    } else {
      if (resolved.own_mask.empty()) resolved.own_mask.assign(skeleton.joint_count(), 1.0f);
      for (size_t j = 0; j < skeleton.joint_count(); ++j)
        resolved.own_mask[j] = std::max(0.0f, resolved.own_mask[j] - layer.weight * layer.mask[j]);
    }
    resolved.layers.push_back(std::move(layer));
  }
  *out = std::move(resolved);
  return {};
}

float layer_time(const Action& own, float time, const Action& layer) {
  const float length = layer.duration();
  if (!(length > 0.0f)) return layer.start;
  return layer.start + std::fmod(std::max(0.0f, time - own.start), length);
}

bool LayeringJob::Validate() const {
  if (!layers || layers->empty() || layers->layers.size() > kMaxAnimLayers || own.empty() || own.size() > 2 || !rest ||
      !output)
    return false;
  return layer_poses.size() == layers->layers.size() && deltas.size() == layers->layers.size();
}

bool LayeringJob::Run() const {
  if (!Validate()) return false;
  BlendLayer blend[2 + kMaxAnimLayers], added[kMaxAnimLayers];
  size_t blended = 0, adds = 0;
  for (const BlendLayer& o : own) blend[blended++] = {o.pose, o.weight, layers->own_mask};
  for (size_t i = 0; i < layers->layers.size(); ++i) {
    const CharacterLayers::Layer& layer = layers->layers[i];
    if (layer.additive) {
      additive_delta(layer_poses[i], layer.reference, &deltas[i]);
      added[adds++] = {&deltas[i], layer.weight, layer.mask};
    } else {
      blend[blended++] = {&layer_poses[i], layer.weight, layer.mask};
    }
  }
  BlendingJob job{std::span<const BlendLayer>(blend, blended), rest, 0.1f, output};
  job.additive_layers = std::span<const BlendLayer>(added, adds);
  return job.Run();
}

}  // namespace crowdprof
