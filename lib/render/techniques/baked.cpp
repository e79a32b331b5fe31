#include "render/techniques/baked.h"

#include <algorithm>
#include <bit>

#include "frame/frame_view.h"
#include "render/gl_errors.h"
#include "render/techniques/buffer_palette.h"
#include "render/techniques/instanced.h"

namespace crowdprof {

namespace {

// `fading`: the variant that also reads a record's second slot (GpuFade) and
// mixes in the action left; the other copies draw with the plain one, as
// without transitions.
std::vector<ShaderStage> baked_stages(PlacementBlock block, const GlFeatures& gl, bool fading = false) {
  return lit_stages(
      "shaders/baked.vert",
      std::string(fading ? "#define FADING\n" : "") + copy_colours_define() + GpuPlacements::shader_source(block, gl),
      "#define INSTANCED\n");
}

}  // namespace

BakedSkinning::BakedSkinning(const GlFeatures& gl) : gl_(gl) {
  program_ = GlProgram(baked_stages(PlacementBlock::Uniform, gl));
  joint_count_ = program_.uniform("joint_count");
}

BakedSkinning::~BakedSkinning() {
  glDeleteBuffers(static_cast<GLsizei>(tables_.size()), tables_.data());
}

void BakedSkinning::prepare(const FrameView& view, CharacterMeshes& meshes) {
  tables_.resize(meshes.size(), 0);
  const auto block = static_cast<uint64_t>(std::max<int64_t>(gl_.max_storage_block_bytes, 0));
  uint64_t bytes = 0;
  for (size_t k = 0; k < meshes.size(); ++k) {
    const BakedCharacter* baked = view.characters[k].site == SkinningSite::Baked ? view.characters[k].baked : nullptr;
    if (!baked) continue;
    meshes.upload_rest_mesh(k);
    std::vector<glm::vec4> rows(3 * baked->matrices.size());
    for (size_t m = 0; m < baked->matrices.size(); ++m) put_rows(baked->matrices[m], &rows[3 * m]);
    uint64_t table_bytes = rows.size() * sizeof(glm::vec4);
    // The vertex shader sees the table as one storage block.
    if (table_bytes > block)
      throw GlUnavailable("the baked table of character " + std::to_string(k + 1) + " (" +
                              std::to_string(baked->matrices.size() / std::max<size_t>(meshes[k].joints, 1)) +
                              " samples of " + std::to_string(meshes[k].joints) + " joints) needs " +
                              std::to_string(table_bytes) + " bytes; a storage block holds " + std::to_string(block) +
                              " (GL_MAX_SHADER_STORAGE_BLOCK_SIZE): ",
                          "lower {bake_rate}, or skin it another way");
    glDeleteBuffers(1, &tables_[k]);
    tables_[k] = make_buffer(GL_SHADER_STORAGE_BUFFER, table_bytes, rows.data(), GL_STATIC_DRAW);
    bytes += table_bytes;
  }
  // A view at the address of one prepared before (a bench made where an
  // earlier one was) takes nothing of its cull pass.
  std::erase_if(culls_, [&](const auto& entry) { return entry.first == &view; });
  const size_t copies = view.copies();
  bytes += std::max<size_t>(copies, 1) * sizeof(GpuPlacement);  // the placements, sent at the first frame
  if (view.mode.frustum != FrustumTest::Gpu) {
    // A record per copy on screen, sent each frame; with transitions two
    // slots for a fading copy (every copy at most).
    const bool fades = view.mode.transitions_s > 0;
    if (fades && !fading_program_.id()) {
      fading_program_ = GlProgram(baked_stages(PlacementBlock::Uniform, gl_, true));
      fading_joint_count_ = fading_program_.uniform("joint_count");
    }
    buffers_.reserve(fades ? 2 * copies : copies, 0, 0, true, gl_);
    gpu_bytes_ = bytes + buffers_.gpu_bytes();
    return;
  }
  // Each character's and level's records in a range as long as the
  // character's copies (any of them may take any level): the cull pass
  // appends to it, and its draw reads it.
  const size_t per_kind = view.mode.mesh_lod ? kMeshLevels : 1, groups = meshes.size() * per_kind;
  std::vector<size_t> first(groups + 1, 0);
  std::vector<uint8_t> baked(meshes.size(), 0);
  for (size_t i = 0; i < copies; ++i)
    for (size_t level = 0; level < per_kind; ++level) ++first[view.kind[i] * per_kind + level + 1];
  for (size_t g = 0; g < groups; ++g) first[g + 1] += first[g];
  for (size_t k = 0; k < meshes.size(); ++k) baked[k] = k < tables_.size() && tables_[k] != 0;
  // The cull pass reads the copies and writes the records as storage blocks.
  const uint64_t record_bytes = uint64_t{per_kind} * sizeof(GpuInstance);
  if (copies * record_bytes > block || copies * GpuCull::kBytesPerCopy > block)
    throw GlUnavailable("frustum gpu's cull pass reads " + std::to_string(GpuCull::kBytesPerCopy) +
                            " bytes a copy and writes " + std::to_string(record_bytes) +
                            " as storage blocks; a block holds " + std::to_string(block) +
                            " bytes (GL_MAX_SHADER_STORAGE_BLOCK_SIZE), room for " +
                            std::to_string(block / std::max(record_bytes, GpuCull::kBytesPerCopy)) + " copies, not " +
                            std::to_string(copies) + ": ",
                        "use fewer copies, or {frustum} cpu");
  buffers_.reserve_gpu_records(first[groups], gl_);
  if (!cull_program_.id() && cull_reads_storage(view)) {
    cull_program_ = GlProgram(baked_stages(PlacementBlock::Storage, gl_));
    cull_joint_count_ = cull_program_.uniform("joint_count");
  }
  culls_.emplace_back(&view, std::make_unique<GpuCull>(view, meshes, first, baked));
  gpu_bytes_ = bytes + buffers_.gpu_bytes() + culls_.back().second->gpu_bytes();
}

bool BakedSkinning::cull_reads_storage(const FrameView& view) const {
  return view.copies() > GpuPlacements::copies_per_page(gl_);
}

GpuCull* BakedSkinning::cull_for(const FrameView& view) const {
  if (view.mode.frustum != FrustumTest::Gpu) return nullptr;
  for (const auto& [owner, cull] : culls_)
    if (owner == &view) return cull.get();
  return nullptr;
}

bool BakedSkinning::visible_counts(const FrameView& view, std::span<uint64_t> per_group) const {
  const GpuCull* cull = cull_for(view);
  if (!cull) return false;
  cull->visible_counts(per_group);
  return true;
}

void BakedSkinning::upload(const FrameView& view, const CharacterMeshes& meshes, Counters& counters) {
  counters.bytes_uploaded += placements_.update(view, gl_);  // nothing once the crowd is placed
  counters.gpu_palette_bytes = gpu_bytes_;
  if (GpuCull* cull = cull_for(view)) return cull->run(view, buffers_.instance_buffer(), counters);
  if (view.mode.frustum == FrustumTest::Gpu)
    throw GlError("frustum gpu asked of a renderer not prepared for this bench");
  for (size_t k = 0; k < meshes.size(); ++k)
    if (view.characters[k].site == SkinningSite::Baked && (k >= tables_.size() || !tables_[k]))
      throw GlError("baked skinning asked of a renderer not prepared for it");
  // This frame's records, one run per character and mesh level (one instanced
  // draw each), in copy order within a run: counted, then added.
  // With transitions, the fading copies' two-slot records follow in runs of
  // their own (groups from `groups` on), drawn by the fading program.
  auto drawn = [&](size_t i) { return view.visible[i] && view.site_of(i) == SkinningSite::Baked; };
  auto fading = [&](size_t i) { return !view.baked_fades.empty() && view.baked_fades[i].fading(); };
  const size_t groups = meshes.size() * kMeshLevels;
  drawn_.assign(view.baked_fades.empty() ? groups : 2 * groups, 0);
  for (size_t i = 0; i < view.copies(); ++i)
    if (drawn(i)) drawn_[draw_group(view, i) + (fading(i) ? groups : 0)] += fading(i) ? 2 : 1;
  buffers_.begin(drawn_);
  fading_records_ = 0;
  for (size_t i = 0; i < view.copies(); ++i) {
    if (!drawn(i)) continue;
    const BakedInstance& b = view.baked[i];
    const size_t joints = meshes[view.kind[i]].joints;
    GpuInstance record;
    record.copy = static_cast<uint32_t>(i);
    record.palette_base = static_cast<uint32_t>(3 * b.first_sample * joints);
    record.source[0] = b.intervals;
    record.source[1] = std::bit_cast<uint32_t>(b.position);
    if (!fading(i)) {
      buffers_.add_record(draw_group(view, i), record);
      continue;
    }
    const BakedFade& f = view.baked_fades[i];
    buffers_.add_fading_record(draw_group(view, i) + groups, record,
                               {static_cast<uint32_t>(3 * f.first_sample * joints), f.intervals, f.position, f.weight});
    ++fading_records_;
  }
  count_record_bytes(counters, buffers_.upload(true).records);
}

void BakedSkinning::draw(const FrameView& view, const CharacterMeshes& meshes, const DrawPass& pass,
                         Counters& counters) {
  const GpuCull* gpu_cull = cull_for(view);
  const bool storage = gpu_cull && cull_reads_storage(view);
  const GlProgram& program = storage ? cull_program_ : program_;
  const GLint joint_count = storage ? cull_joint_count_ : joint_count_;
  glUseProgram(program.id());
  set_frame_uniforms(program, pass);
  set_copy_colours(program);
  auto bind_table = [&](size_t k, GLint joints_at) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kPaletteBinding, tables_[k]);
    glUniform1ui(joints_at, static_cast<GLuint>(meshes[k].joints));
  };
  if (!gpu_cull) {
    draw_instance_runs(
        buffers_, placements_, meshes, view.mode.index_order, [&](size_t k) { bind_table(k, joint_count); }, counters);
    if (fading_records_ == 0) return;
    glUseProgram(fading_program_.id());
    set_frame_uniforms(fading_program_, pass);
    set_copy_colours(fading_program_);
    return draw_instance_runs(buffers_, placements_, meshes, view.mode.index_order,
                              [&](size_t k) { bind_table(k, fading_joint_count_); }, counters,
                              {meshes.size() * kMeshLevels, 2});
  }
  // The cull pass's copies fit one storage block (prepare), and their placements, smaller, too.
  static_assert(sizeof(GpuPlacement) <= GpuCull::kBytesPerCopy);
  if (storage)
    placements_.bind_storage();
  else
    placements_.bind_page(0);
  for (size_t k = 0; k < meshes.size(); ++k) {
    if (k >= tables_.size() || !tables_[k]) continue;
    bind_table(k, joint_count);
    gpu_cull->draw(k, meshes[k], buffers_.instance_buffer(), counters);
  }
  glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);  // no later draw reads commands by accident
}

}  // namespace crowdprof
