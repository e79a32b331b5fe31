// The per-frame buffers of GPU-skinned copies in the buffer, instanced and
// baked modes: every palette drawn this frame in one shader storage buffer
// (none for baked, whose palettes are its table), and one 16-byte record per
// instance (the copy, its palette offset, two words of the skinning source's)
// in another, read as per-instance vertex attributes (shaders/instances.glsl
// says the layout). What never changes for a copy, its placement, is not in
// the record: it was sent once (render/gpu_placements.h) and the record names
// the copy.
//
// Paged palettes (issue 30): a shader may see at most one storage block of the
// palette buffer (GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 128 MiB on llvmpipe: about
// 40,000 humanoids), but the buffer may be larger. It is cut into pages of at
// most a block, each starting where a bound range may start; no palette spans
// two. A record's palette_base counts rows from its page's start, and a draw
// binds its page's range (bind_page) first: per copy, or one instanced draw per
// run of a kind's records on one page (page_run).
//
// Another skinning source draws through the same records (mode baked: its
// actions' samples in a table of its own): reserve() with no palette rows,
// then each frame begin() the runs and add_record() each copy's record, whose
// palette_base and source words are the source's own (baked: where the copy's
// action starts in the table, its interval count and its position among its
// samples), upload(), bind its own table at kPaletteBinding and draw with
// draw_instance_runs (render/techniques/instanced.h), as instanced does. Its
// vertex shader reads the records as per-instance attributes (not a storage
// block, whose size limit would cap the copies a draw takes): instance_buffer()
// at vertex binding kInstanceStream with offset first x 16 and divisor 1,
// (copy, palette_base, source0, source1) as a uvec4 at location
// kInstanceAttribute, as the renderer's instanced VAOs do
// (render/character_meshes.cpp). Records name their copy from the first of
// its page of placements (gpu_placements.h): a draw takes records of one page
// of palettes and one of placements. A compute pass may write the records itself
// (frustum gpu: render/techniques/gpu_cull.h): reserve_gpu_records() gives the
// buffer its storage.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "render/gl.h"
#include "render/gl_features.h"
#include "render/gpu_placements.h"

namespace crowdprof {

// One instance's record (shaders/instances.glsl; baked.vert and cull.comp
// read and write the same): what a copy on screen sends each frame.
struct GpuInstance {
  uint32_t copy = 0;          // the copy, from its page of placements' first (gpu_placements.h)
  uint32_t palette_base = 0;  // the palette's first row in the palette buffer (baked: its action's in the table)
  uint32_t source[2] = {0, 0};
};
static_assert(sizeof(GpuInstance) == 16, "one uvec4 attribute");

// The second half of a fading baked copy's record (issue 53; baked.vert's
// fade_data): the action it leaves, where that one's samples start in the
// table, its interval count and the copy's position among them, and the
// weight the shader gives it. A fading copy sends 32 bytes, a GpuInstance and
// this; the others 16.
struct GpuFade {
  uint32_t palette_base = 0;
  uint32_t intervals = 1;
  float position = 0.0f;
  float weight = 0.0f;
};
static_assert(sizeof(GpuFade) == sizeof(GpuInstance), "the record's second slot");

// The palettes' binding point, as shaders/instances.glsl names it.
inline constexpr GLuint kPaletteBinding = 0;
// The vertex buffer binding an instanced draw reads the records from, and
// the attribute location they arrive at.
inline constexpr GLuint kInstanceStream = 4;
inline constexpr GLuint kInstanceAttribute = 4;
// Where a two-slot record's second slot arrives (GpuFade), from the same
// stream; enabled only for the draws of two-slot records.
inline constexpr GLuint kFadeAttribute = 5;

// Bytes one frame sent: palette rows and instance records apart.
struct SentBytes {
  uint64_t palettes = 0, records = 0;
  uint64_t total() const { return palettes + records; }
};

// Where one kind's instances are in this frame's records.
struct InstanceRun {
  uint32_t first = 0, count = 0;
};

class GpuFrameBuffers {
 public:
  GpuFrameBuffers() = default;
  ~GpuFrameBuffers();
  GpuFrameBuffers(const GpuFrameBuffers&) = delete;
  GpuFrameBuffers& operator=(const GpuFrameBuffers&) = delete;

  // Makes room (on the CPU and the GPU) for `instances` records (sent only
  // `with_instances`) and `rows` palette rows, none longer than `largest_rows`,
  // in pages of the largest storage block `gl` allows; growing keeps nothing.
  // With no rows (largest_rows 0) there is no palette buffer: records only.
  // Throws GlUnavailable, naming the limit and the most copies that fit, when a
  // palette exceeds a page or the buffers the GPU's free memory (where the GL
  // says it). The records are read as vertex attributes: no block bounds them.
  void reserve(size_t instances, size_t rows, size_t largest_rows, bool with_instances, const GlFeatures& gl);

  // Room on the GPU only for `records` records that a compute pass writes
  // (frustum gpu: gpu_cull.h) and the draws read; the CPU keeps none. Throws
  // GlUnavailable past the GPU's free memory (where the GL says it), naming it
  // and how many records fit.
  void reserve_gpu_records(size_t records, const GlFeatures& gl);

  // Starts a frame: kind k gets `counts[k]` records, one run after another,
  // which add() fills in order. `counts` must fit the reservation.
  void begin(std::span<const uint32_t> counts);
  // Appends a record of `copy` for `kind`; returns its 3 x joints palette rows
  // (empty for 0) to fill, which it points palette_base at.
  std::span<glm::vec4> add(size_t kind, uint32_t copy, size_t palette_rows);
  // Appends a record for `kind` that sends no palette (another skinning
  // source: its palette_base and source words as given, its copy counted from
  // 0 and stored from its page's first); on palette page 0.
  void add_record(size_t kind, const GpuInstance& record);
  // As add_record, with `fade` in the slot after the record: a run of such
  // records counts two slots each (begin's counts too) and is drawn with
  // RecordSlots 2 (draw_instance_runs).
  void add_fading_record(size_t kind, const GpuInstance& record, const GpuFade& fade);
  // The records and rows added since begin().
  InstanceRun run(size_t kind) const { return runs_[kind]; }
  // Counted from the start of the record's page.
  uint32_t palette_base(uint32_t record) const { return instances_[record].palette_base; }
  uint32_t page_of(uint32_t record) const { return page_of_[record]; }
  // The page of placements the record's copy is on (GpuPlacements::bind_page).
  uint32_t placement_page_of(uint32_t record) const { return placement_page_of_[record]; }
  // The records of `kind`'s run from `from` on that are on from's pages.
  InstanceRun page_run(size_t kind, uint32_t from) const;
  // Binds page `page` of the palettes at kPaletteBinding (nothing when the
  // buffers hold records only).
  void bind_page(uint32_t page) const;

  // Sends the palette rows (and, with `with_instances`, the records) to the GPU
  // in fresh storage (orphaned, so no draw of the last frame is waited for) and
  // binds the palettes' first page at kPaletteBinding. Returns the bytes sent.
  // The records sent are those of the runs begin() reserved.
  SentBytes upload(bool with_instances);

  // Bytes of GPU storage the two buffers hold.
  uint64_t gpu_bytes() const { return palette_capacity_bytes_ + instance_capacity_bytes_; }
  uint64_t palette_gpu_bytes() const { return palette_capacity_bytes_; }
  // The records' buffer, for binding as per-instance vertex attributes.
  GLuint instance_buffer() const { return instance_buffer_; }

 private:
  // Gives the records' buffer storage for `bytes` now, when it has less.
  void grow_instance_storage(uint64_t bytes);

  std::vector<GpuInstance> instances_;
  std::vector<glm::vec4> rows_;
  std::vector<InstanceRun> runs_;
  std::vector<uint32_t> filled_;             // per kind, records added so far
  std::vector<uint32_t> page_of_;            // per record
  std::vector<uint32_t> placement_page_of_;  // per record
  size_t placement_page_copies_ = 1;
  size_t rows_used_ = 0;
  size_t page_rows_ = 0;  // rows a page holds
  GLuint palette_buffer_ = 0, instance_buffer_ = 0;
  uint64_t palette_capacity_bytes_ = 0, instance_capacity_bytes_ = 0;
};

}  // namespace crowdprof
