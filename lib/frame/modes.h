// The thesis's ladder of modes as data: each mode is a named preset of
// independent switches, and a user can set any switch on its own.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

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
};

// What CPU skinning writes for the GPU to read (skinning/packed_vertex.h).
enum class VertexFormat : uint8_t {
  Float,   // positions and normals as 32-bit floats, 24 bytes a vertex
  Packed,  // positions quantised to 16 bits in the character's box, normals 10:10:10:2: 10 bytes
};

struct ModeSwitches {
  Lookups lookups = Lookups::Bundled;
  bool animation_culling = false;  // §4.1: no pose or skinning for copies off-screen
  PoseStorage pose = PoseStorage::PerCopy;
  bool parallel = false;  // pose updates (and CPU skinning in Animations) on oneTBB
  SkinningSite skinning = SkinningSite::CpuInAnimations;
  VertexFormat vertex_format = VertexFormat::Float;  // no preset packs; --vertex-format

  bool operator==(const ModeSwitches&) const = default;
};

struct ModePreset {
  std::string_view name;
  std::string_view summary;
  ModeSwitches switches;
};

// master, culled, threaded, hwskin.
std::span<const ModePreset> mode_presets();
// Null when there is no such preset.
const ModePreset* find_mode(std::string_view name);
// "master, culled, threaded, hwskin".
std::string mode_names();

// Empty when the switches can run together, else why not (e.g. a shared scratch
// pose cannot be filled by several threads at once).
std::string conflicts(const ModeSwitches& switches);

std::string_view to_string(Lookups lookups);
std::string_view to_string(PoseStorage pose);
std::string_view to_string(SkinningSite site);
std::string_view to_string(VertexFormat format);

}  // namespace crowdprof
