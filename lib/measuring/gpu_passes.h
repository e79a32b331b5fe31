// A frame's GPU work split by pass (issue 30): the time each kind of pass took
// (GL_TIMESTAMP queries at each boundary) and, where the GL has
// ARB_pipeline_statistics_query, what it pushed through the pipeline. Not
// categories: the GPU runs beside the CPU's frame, and the passes add up to
// the frame's GPU time, not to the frame.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <vector>

namespace crowdprof {

// In the order a frame runs them. Skinning: what the GPU does before the first
// draw (compute skinning's dispatches, buffer uploads); each draw pass is the
// crowd drawn into its own target (modes.h's passes).
enum class GpuPass : uint8_t { Skinning, Prepass, Shadows, Colour };
inline constexpr size_t kGpuPassCount = 4;
inline constexpr std::array<std::string_view, kGpuPassCount> kGpuPassNames = {"skinning", "prepass", "shadows",
                                                                              "colour"};

// ARB_pipeline_statistics_query's counters crowdprof reads, per pass.
enum class PipelineStat : uint8_t {
  VerticesSubmitted,
  PrimitivesSubmitted,
  VertexShaderInvocations,
  FragmentShaderInvocations,
  ComputeShaderInvocations
};
inline constexpr size_t kPipelineStatCount = 5;
inline constexpr std::array<std::string_view, kPipelineStatCount> kPipelineStatNames = {
    "vertices_submitted", "primitives_submitted", "vertex_shader_invocations", "fragment_shader_invocations",
    "compute_shader_invocations"};

// Whether a frame of `passes` draws (modes.h) runs `pass`: skinning and
// colour always, the prepass from 2 passes, shadows from 3.
inline bool pass_drawn(GpuPass pass, uint32_t passes) {
  if (pass == GpuPass::Prepass) return passes >= 2;
  if (pass == GpuPass::Shadows) return passes >= 3;
  return true;
}

// One frame's figures; NaN where a figure was not read (no timer, no
// statistics query, or not read back).
struct GpuPassFigures {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  std::array<double, kGpuPassCount> ms{kNone, kNone, kNone, kNone};
  std::array<std::array<double, kPipelineStatCount>, kGpuPassCount> stats{{{kNone, kNone, kNone, kNone, kNone},
                                                                           {kNone, kNone, kNone, kNone, kNone},
                                                                           {kNone, kNone, kNone, kNone, kNone},
                                                                           {kNone, kNone, kNone, kNone, kNone}}};

  bool timed() const { return ms[0] == ms[0]; }
  bool has_stats() const { return stats[0][0] == stats[0][0]; }
};

// Each drawn pass's median time over the frames that timed it, and the sum of
// those medians, which the passes' coverage of the frame's GPU time divides.
// The text report, the JSON and the HTML report all print these.
struct GpuPassMedians {
  std::array<std::optional<double>, kGpuPassCount> median;  // empty: not drawn, or never timed
  double sum = 0;
};
// `ms[p]`: pass p's time per frame, NaN where it was not timed.
GpuPassMedians gpu_pass_medians(const std::array<std::vector<double>, kGpuPassCount>& ms, uint32_t passes);

}  // namespace crowdprof
