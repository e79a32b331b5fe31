// One way of getting skinned copies onto the screen (docs/rendering.md). Each
// technique owns its GL programs and buffers; the renderer picks the ones the
// frame's copies need from the mode's switches and each draws its copies:
//   software_upload  CPU-skinned vertices uploaded every frame (float or packed)
//   uniform_palette  vertex-shader skinning, the palette as a uniform array (hwskin)
//   buffer_palette   vertex-shader skinning, palettes in a storage buffer, a draw per copy
//   instanced        the same palettes, one instanced draw per character
//   compute          a compute pass skins into a buffer the draws read
//   baked            palettes sampled at load, one instanced draw per character
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "animation/skin_matrix.h"
#include "measuring/counters.h"
#include "render/gl.h"
#include "render/draw_passes.h"
#include "render/gl_program.h"

namespace crowdprof {

struct FrameView;
class CharacterMeshes;

// A few colours so that neighbours in the crowd can be told apart.
inline constexpr std::array<glm::vec3, 6> kCopyColours = {{{0.80f, 0.45f, 0.30f},
                                                           {0.35f, 0.55f, 0.80f},
                                                           {0.55f, 0.75f, 0.40f},
                                                           {0.85f, 0.75f, 0.35f},
                                                           {0.65f, 0.45f, 0.75f},
                                                           {0.75f, 0.75f, 0.75f}}};

inline const glm::vec3& copy_colour(size_t copy) {
  return kCopyColours[copy % kCopyColours.size()];
}

// A new buffer bound at `target`, of `bytes` (from `data` when not null).
GLuint make_buffer(GLenum target, size_t bytes, const void* data, GLenum usage);

// The 3x4 upper part of a column-major matrix, as rows (the fourth row of an
// affine matrix is always 0 0 0 1): how every palette goes to the GPU.
void put_rows(const SkinMatrix& m, glm::vec4* rows);

// A lit program's stages: shaders `vertex` with `defines`, then shaders/lit.frag.
std::vector<ShaderStage> lit_stages(const char* vertex, const std::string& defines,
                                    const std::string& fragment_defines = {});

// What every lit program takes each pass: the pass's camera and the light.
void set_frame_uniforms(const GlProgram& program, const DrawPass& pass);

// Bytes a copy's world matrix costs to send.
inline constexpr uint64_t kModelBytes = sizeof(glm::mat4);

// Bytes sent for GPU skinning, counted in bytes_uploaded and in their part:
// palettes, or per-copy records (an instance record, a draw's model matrix).
inline void count_palette_bytes(Counters& counters, uint64_t bytes) {
  counters.bytes_uploaded += bytes;
  counters.palette_bytes_uploaded += bytes;
}
inline void count_record_bytes(Counters& counters, uint64_t bytes) {
  counters.bytes_uploaded += bytes;
  counters.record_bytes_uploaded += bytes;
}

class Technique {
 public:
  virtual ~Technique() = default;
  // Once a frame, before any pass: sends what the draws read this frame
  // (palettes, skinned vertices, instance records), adding it to
  // counters.bytes_uploaded (and gpu_palette_bytes: what it holds there).
  virtual void upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) = 0;
  // Draws this frame's copies on screen that use the technique into the
  // target bound, as `pass` sees them; adds draws (and what each sends) to
  // `counters`.
  virtual void draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass, Counters& counters) = 0;
};

}  // namespace crowdprof
