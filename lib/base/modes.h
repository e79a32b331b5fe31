// The thesis's ladder of modes as data: each mode is a named preset of
// independent switches, and a user can set any switch on its own.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/anim_layers.h"
#include "base/errors.h"

namespace crowdprof {

// How sampling finds the joint each channel drives (§4.2).
enum class Lookups : uint8_t {
  PerFrameString,  // every channel's RNA path parsed and searched, every frame
  Bundled,         // resolved once at load
};

// Where the pose of each copy is built (the BGE's bPose swap, §4.3).
enum class PoseStorage : uint8_t {
  SharedScratch,  // one scratch pose that every copy is sampled into in turn
  PerCopy,        // each copy owns its pose, so copies can run in parallel
};

// Where vertices are skinned, and so which category pays for it.
enum class SkinningSite : uint8_t {
  CpuInRasterizer,  // the BGE before the thesis: deformers ran in the render stage
  CpuInAnimations,  // §4.3: skinning runs with the pose update, in parallel
  Gpu,              // §4.4: the vertex shader (needs a GL backend)
  // Beyond the thesis (issue 12), both on the GPU, with no bone limit:
  Compute,  // a compute pass skins every visible copy into a vertex buffer, then plain draws
  Baked,    // actions baked at load; the vertex shader interpolates the baked matrices
};

// True for the sites where the GPU, not the CPU, skins vertices.
constexpr bool skins_on_gpu(SkinningSite site) {
  return site == SkinningSite::Gpu || site == SkinningSite::Compute || site == SkinningSite::Baked;
}

// Where the skinning matrices of copies skinned on the GPU live (beyond the
// thesis, whose own future work names buffers for more bones).
enum class PaletteStorage : uint8_t {
  Uniforms,  // 4.4: a uniform array per draw, at most 128 bones
  Buffer,    // one shader storage buffer (SSBO) for every copy: no bone limit
};

// How copies skinned on the GPU are submitted.
enum class DrawMethod : uint8_t {
  PerCopy,    // one draw call per copy on screen, as the BGE drew
  Instanced,  // one draw call per character kind and material; each instance
              // reads its transform and palette offset from a buffer
};

// Where copies are tested against the camera's frustum and the draw list made
// (issue 30). GPU-driven crowds decide both on the GPU, so the CPU's cost per
// frame does not grow with the crowd.
enum class FrustumTest : uint8_t {
  Cpu,  // each frame in Scenegraph, every copy's box; the CPU lists the draws
  Gpu,  // a compute pass tests the boxes and writes the instance records and
        // indirect draw commands; the CPU submits one indirect draw per character
};

// What CPU skinning writes for the GPU to read (skinning/packed_vertex.h).
enum class VertexFormat : uint8_t {
  Float,   // positions and normals as 32-bit floats, 24 bytes a vertex
  Packed,  // positions quantised to 16 bits in the character's box, normals 10:10:10:2: 10 bytes
};

// The order an index buffer lists each mesh's triangles in for the GPU
// (issue 52). The GPU shades a vertex again when it has left its post-
// transform cache; files rarely order triangles for it, so most vertices are
// shaded about twice.
enum class IndexOrder : uint8_t {
  File,       // as the file lists them
  Optimized,  // meshoptimizer's vertex-cache order; the vertices keep skinning's order
};

// How a copy fades into its next action (issue 53).
enum class Crossfade : uint8_t {
  Frozen,   // toward the pose it had when the change came, one action sampled a frame (the BGE's)
  Sampled,  // both actions sampled every frame of the fade (blend trees': ozz, Unreal)
};

// Update-rate LOD (issue 13): a copy whose box spans at least lod[0] of the
// screen's height is updated every frame, at least lod[1] every 2nd frame, at
// least lod[2] every 4th, smaller ones every 8th. Between updates a copy holds
// its last pose (it is not interpolated).
struct LodThresholds {
  float every_1 = 0.25f, every_2 = 0.125f, every_4 = 0.0625f;
  bool operator==(const LodThresholds&) const = default;
};

// Mesh LOD (issue 29): a copy whose box spans at least level_1 of the screen's
// height draws the full mesh, at least level_2 the first simplified level, at
// least level_3 the second, smaller ones the third (asset/mesh_lod.h). A copy
// coarsens as soon as it is below a threshold, and refines only once it is
// kMeshLodHysteresis above it, so one at a threshold does not flicker.
struct MeshLodThresholds {
  float level_1 = 0.25f, level_2 = 0.125f, level_3 = 0.0625f;
  bool operator==(const MeshLodThresholds&) const = default;
};
inline constexpr float kMeshLodHysteresis = 0.15f;

// Most draws of the crowd a frame (--passes): a prepass, 8 shadow cascades, colour.
inline constexpr uint32_t kMaxPasses = 10;

struct ModeSwitches {
  Lookups lookups = Lookups::Bundled;
  bool animation_culling = false;  // §4.1: no pose or skinning for copies off-screen
  PoseStorage pose = PoseStorage::PerCopy;
  bool parallel = false;  // pose updates (and CPU skinning in Animations) on oneTBB
  SkinningSite skinning = SkinningSite::CpuInAnimations;
  PaletteStorage palettes = PaletteStorage::Uniforms;
  DrawMethod draw = DrawMethod::PerCopy;
  // Animation sharing (issue 13): copies showing the same action at the same
  // time share one pose evaluation and one skinned mesh.
  bool share_poses = false;
  // Seconds; > 0 snaps each copy's time to the nearest multiple of it (from its
  // action's start) so that copies fall into shared states. 0: exact times.
  double share_quantum_s = 0.0;
  bool update_lod = false;  // copies updated every 1, 2, 4 or 8 frames by size on screen
  LodThresholds lod;
  // > 0: the Animations category is held at or under this many ms (its p95) by
  // updating the copies smallest on screen less often (lib/animation/update_rates.h).
  double anim_budget_ms = 0.0;
  VertexFormat vertex_format = VertexFormat::Float;  // no preset packs; --vertex-format
  // Times the crowd is drawn a frame (issue 30): 1, colour only; 2, a depth
  // prepass then colour; N > 2, the prepass, N - 2 shadow cascades, colour.
  uint32_t passes = 1;
  FrustumTest frustum = FrustumTest::Cpu;
  bool mesh_lod = false;  // far copies skin and draw simplified meshes
  MeshLodThresholds mesh_lod_at;
  IndexOrder index_order = IndexOrder::Optimized;  // results without it ran in File order
  // Transitions (issue 53): > 0, each copy changes action after about this
  // many seconds (scene/transitions.h), fading over blend_in_s.
  double transitions_s = 0.0;
  double blend_in_s = 0.25;
  Crossfade crossfade = Crossfade::Sampled;
  // Layers (issue 56): actions laid over each copy's, in order.
  std::vector<AnimLayer> anim_layers;

  bool operator==(const ModeSwitches&) const = default;
};

struct ModePreset {
  std::string_view name;
  std::string_view summary;
  ModeSwitches switches;
};

// master, culled, threaded, hwskin (the thesis's), then buffer, instanced, shared,
// budget, compute, baked.
std::span<const ModePreset> mode_presets();
// Null when there is no such preset.
const ModePreset* find_mode(std::string_view name);
// "master, culled, threaded, hwskin, buffer, instanced, shared, budget, compute, baked".
std::string mode_names();

// Empty when the switches can run together, else why not (e.g. a shared scratch
// pose cannot be filled by several threads at once), naming the switches.
SettingText conflicts(const ModeSwitches& switches);

std::string_view to_string(Lookups lookups);
std::string_view to_string(PoseStorage pose);
std::string_view to_string(SkinningSite site);
std::string_view to_string(VertexFormat format);
std::string_view to_string(PaletteStorage palettes);  // "uniforms", "buffer"
std::string_view to_string(DrawMethod draw);          // "per-copy", "instanced"
std::string_view to_string(FrustumTest frustum);      // "cpu", "gpu"
std::string_view to_string(IndexOrder order);         // "file", "optimized"
std::string_view to_string(Crossfade crossfade);      // "frozen", "sampled"

}  // namespace crowdprof
