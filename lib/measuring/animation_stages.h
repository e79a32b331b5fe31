// The Animations category split by stage (issue 53 item 4): what each pose
// update spent sampling its action(s), blending a fade, building model-space
// and skinning matrices, and skinning its mesh on the CPU. Not categories: the
// stages run on every bench thread at once, so each is the thread time summed
// over the threads, and they add up to Animations' wall time only on one
// thread (the rest is scheduling and waiting). The BGE's table keeps its ten
// categories; the split goes into JSON, the trace, the HTML report and a line
// of the text report.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace crowdprof {

enum class AnimationStage : uint8_t { Sampling, Blending, LocalToModel, Skinning };
inline constexpr size_t kAnimationStageCount = 4;
// JSON names, "local_to_model"; the trace's and reports' labels are these too.
inline constexpr std::array<std::string_view, kAnimationStageCount> kAnimationStageNames = {
    "sampling", "blending", "local_to_model", "skinning"};
// "local-to-model": for text and tables.
inline constexpr std::array<std::string_view, kAnimationStageCount> kAnimationStageLabels = {
    "sampling", "blending", "local-to-model", "skinning"};

// The stage's series of per-frame thread milliseconds: "animation_sampling_ms".
inline std::string animation_stage_series(size_t stage) {
  return "animation_" + std::string(kAnimationStageNames[stage]) + "_ms";
}

// One frame's thread milliseconds per stage.
struct AnimationStageTimes {
  std::array<double, kAnimationStageCount> ms{};
  double total_ms() const { return ms[0] + ms[1] + ms[2] + ms[3]; }
};

}  // namespace crowdprof
