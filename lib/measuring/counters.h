// The work a frame did, counted: these depend on the scene and the mode, never
// on the machine, so CI can compare them exactly.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string_view>

#include "measuring/animation_stages.h"
#include "measuring/category_clock.h"
#include "measuring/gpu_passes.h"

namespace crowdprof {

struct Counters {
  uint64_t poses_updated = 0;     // poses sampled and rebuilt: one per copy posed, or per shared state
  uint64_t copies_culled = 0;     // copies skipped by animation culling
  uint64_t copies_visible = 0;    // copies inside the camera's frustum (drawn)
  uint64_t vertices_skinned = 0;  // vertices skinned on the CPU
  uint64_t channel_lookups = 0;   // string-path lookups (zero with bundled lookups)
  uint64_t bytes_uploaded = 0;    // vertex data and bone matrices sent to the GPU
  // Of bytes_uploaded (issue 52): GPU skinning's palettes, and its per-copy
  // records (instanced and baked's instance records; a draw's model matrix).
  uint64_t palette_bytes_uploaded = 0, record_bytes_uploaded = 0;
  uint64_t draw_calls = 0;
  uint64_t copies_fallback = 0;  // copies skinned on the CPU although the mode skins on the GPU
  // GPU memory the palettes of GPU-skinned copies live in: the uniform array
  // (--palettes uniforms), or the storage buffers of every copy's palette (and
  // with --draw instanced, their instance records); with skinning compute, its
  // palette and skinned-vertex buffers; with baked, its baked tables and
  // instance records (and frustum gpu's copies and commands); 0 when none is
  // skinned there.
  uint64_t gpu_palette_bytes = 0;
  // Issue 13: copies that took a new pose this frame (shared or their own),
  // copies on their update-rate LOD or budget's off frame that held their last
  // one, and the updates by the period the copy was at (every 1 to 64 frames).
  uint64_t copies_updated = 0;
  uint64_t copies_held = 0;
  uint64_t updates_every_1 = 0, updates_every_2 = 0, updates_every_4 = 0, updates_every_8 = 0;
  uint64_t updates_every_16 = 0, updates_every_32 = 0, updates_every_64 = 0;
  // Mesh LOD (issue 29), per level (0: the full mesh; 1 to 3 coarser): copies
  // drawn at it, vertices skinned at it (on the CPU, or by the GPU for the
  // copies it skins: once a frame, whatever the passes) and triangles drawn
  // (one pass). Without mesh LOD every copy counts at level 0.
  uint64_t lod0_copies = 0, lod1_copies = 0, lod2_copies = 0, lod3_copies = 0;
  uint64_t lod0_vertices = 0, lod1_vertices = 0, lod2_vertices = 0, lod3_vertices = 0;
  uint64_t lod0_triangles = 0, lod1_triangles = 0, lod2_triangles = 0, lod3_triangles = 0;
  // Vertices of the meshes drawn in one pass: over the copies on screen (with
  // frustum gpu, as the cull pass counted them), their level's vertex count.
  // What each pass's vertex-shader invocations are divided by (vertex reuse).
  uint64_t vertices_drawn = 0;
  // Transitions (issue 53): actions sampled (one per pose evaluation, two for
  // a fade that samples the action it leaves), evaluations of fading copies,
  // and joints blended in them.
  uint64_t actions_sampled = 0, fades = 0, joints_blended = 0;
  // Layers (--anim-layer, issue 56): layers laid, one per layer of each pose
  // evaluated.
  uint64_t layers = 0;
};

struct CounterField {
  std::string_view name;
  uint64_t Counters::*member;
};
// Every counter with its report name, in report order.
inline constexpr std::array<CounterField, 37> kCounterFields = {{
    {"poses_updated", &Counters::poses_updated},
    {"copies_culled", &Counters::copies_culled},
    {"copies_visible", &Counters::copies_visible},
    {"vertices_skinned", &Counters::vertices_skinned},
    {"channel_lookups", &Counters::channel_lookups},
    {"bytes_uploaded", &Counters::bytes_uploaded},
    {"draw_calls", &Counters::draw_calls},
    {"copies_fallback", &Counters::copies_fallback},
    {"gpu_palette_bytes", &Counters::gpu_palette_bytes},
    {"copies_updated", &Counters::copies_updated},
    {"copies_held", &Counters::copies_held},
    {"updates_every_1", &Counters::updates_every_1},
    {"updates_every_2", &Counters::updates_every_2},
    {"updates_every_4", &Counters::updates_every_4},
    {"updates_every_8", &Counters::updates_every_8},
    {"updates_every_16", &Counters::updates_every_16},
    {"updates_every_32", &Counters::updates_every_32},
    {"updates_every_64", &Counters::updates_every_64},
    {"lod0_copies", &Counters::lod0_copies},
    {"lod1_copies", &Counters::lod1_copies},
    {"lod2_copies", &Counters::lod2_copies},
    {"lod3_copies", &Counters::lod3_copies},
    {"lod0_vertices", &Counters::lod0_vertices},
    {"lod1_vertices", &Counters::lod1_vertices},
    {"lod2_vertices", &Counters::lod2_vertices},
    {"lod3_vertices", &Counters::lod3_vertices},
    {"lod0_triangles", &Counters::lod0_triangles},
    {"lod1_triangles", &Counters::lod1_triangles},
    {"lod2_triangles", &Counters::lod2_triangles},
    {"lod3_triangles", &Counters::lod3_triangles},
    {"vertices_drawn", &Counters::vertices_drawn},
    {"actions_sampled", &Counters::actions_sampled},
    {"fades", &Counters::fades},
    {"joints_blended", &Counters::joints_blended},
    {"palette_bytes_uploaded", &Counters::palette_bytes_uploaded},
    {"record_bytes_uploaded", &Counters::record_bytes_uploaded},
    {"layers", &Counters::layers},
}};
// The per-frame CSV's columns never move: its counters up to
// record_bytes_uploaded come before gpu_ms, cpu_ms and the stages' columns,
// those added since after them.
inline constexpr size_t kCsvCountersBeforeGpu = 36;
static_assert(kCounterFields[kCsvCountersBeforeGpu - 1].name == "record_bytes_uploaded");
// The lod*_ counters of level L.
inline constexpr uint64_t Counters::*kLodCopies[4] = {&Counters::lod0_copies, &Counters::lod1_copies,
                                                      &Counters::lod2_copies, &Counters::lod3_copies};
inline constexpr uint64_t Counters::*kLodVertices[4] = {&Counters::lod0_vertices, &Counters::lod1_vertices,
                                                        &Counters::lod2_vertices, &Counters::lod3_vertices};
inline constexpr uint64_t Counters::*kLodTriangles[4] = {&Counters::lod0_triangles, &Counters::lod1_triangles,
                                                         &Counters::lod2_triangles, &Counters::lod3_triangles};
// The updates_every_* counter of period 2^shift.
inline constexpr uint64_t Counters::*kUpdatesByShift[7] = {
    &Counters::updates_every_1,  &Counters::updates_every_2,  &Counters::updates_every_4, &Counters::updates_every_8,
    &Counters::updates_every_16, &Counters::updates_every_32, &Counters::updates_every_64};

struct FrameRecord {
  FrameTimes times;
  Counters counters;
  // CPU time the whole process (every thread) spent in the frame, ms: unlike
  // the wall-clock frame it does not grow while the machine's other jobs hold
  // the cores (check --metric cpu).
  double cpu_ms = 0;
  // The calibration probe's time right after the frame (frame/calibration_probe.h),
  // ms; 0 when the run was not calibrated.
  double probe_ms = 0;
  // Animations by stage, thread time summed over the threads
  // (measuring/animation_stages.h).
  AnimationStageTimes animation_stages;
  // The GPU's time for the frame from a GL timer query (GL_TIME_ELAPSED), ms;
  // NaN when not measured (no GL backend, no timer, or not read back). Not a
  // category: the GPU runs beside the CPU's frame, not in it.
  double gpu_ms = std::numeric_limits<double>::quiet_NaN();
  // The same GPU time split by pass, with pipeline statistics (gpu_passes.h).
  GpuPassFigures gpu_passes;
  // Instructions the frame's thread retired (measuring/instruction_counter.h,
  // perf_event); 0 when not counted or counted by callgrind.
  uint64_t instructions = 0;
  // Copies whose update period the budget changed in this frame. Not a
  // counter: it follows the frame's measured time, so two runs differ.
  uint64_t rate_switches = 0;
};

}  // namespace crowdprof
