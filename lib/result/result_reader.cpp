#include "result/result_codec.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/errors.h"
#include "asset/gltf_container.h"
#include "base/switch_table.h"
#include "result/result_keys.h"
#include "measuring/stats.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// More threads than any machine crowdprof runs on has.
constexpr uint64_t kMaxRecordedThreads = 4096;

// The counters every format-1 result has; later ones are optional.
constexpr std::string_view kRequiredCounters[] = {"poses_updated",    "copies_culled",   "copies_visible",
                                                  "vertices_skinned", "channel_lookups", "bytes_uploaded",
                                                  "draw_calls"};

using result_keys::counter_field;
using result_keys::kCharacterCounters;
using result_keys::pass_samples_key;

// "/scene/file" as users read it: "scene.file".
std::string dotted(const std::string& pointer) {
  std::string out = pointer.substr(1);
  for (char& c : out)
    if (c == '/') c = '.';
  return out;
}

// Unsigned, or signed and not negative: nlohmann keeps the C++ type it was given.
bool whole(const json& value) {
  return value.is_number_unsigned() || (value.is_number_integer() && value.get<int64_t>() >= 0);
}

bool milliseconds(const json& value) {
  return value.is_number() && std::isfinite(value.get<double>()) && value.get<double>() >= 0;
}

// Reads one document, naming `path` and the field in every error.
class Reader {
 public:
  Reader(const json& doc, const std::string& path) : doc_(doc), path_(path) {}

  [[noreturn]] void fail(const std::string& why) const { throw InputError(path_, why); }

  void require(bool ok, const std::string& pointer, const char* expected) const {
    if (!ok) fail("\"" + dotted(pointer) + "\" should be " + expected);
  }

  bool has(const std::string& pointer) const { return doc_.contains(json::json_pointer(pointer)); }

  const json& at(const std::string& pointer) const {
    if (!has(pointer)) fail("not a complete crowdprof result: no \"" + dotted(pointer) + "\"");
    return doc_.at(json::json_pointer(pointer));
  }

  std::string text(const std::string& pointer) const {
    const json& v = at(pointer);
    require(v.is_string(), pointer, "a string");
    return v.get<std::string>();
  }
  std::string text_or(const std::string& pointer, std::string otherwise) const {
    return has(pointer) ? text(pointer) : otherwise;
  }
  uint64_t count(const std::string& pointer) const {
    const json& v = at(pointer);
    require(whole(v), pointer, "a whole number");
    return v.get<uint64_t>();
  }
  uint64_t count_or(const std::string& pointer, uint64_t otherwise) const {
    return has(pointer) ? count(pointer) : otherwise;
  }
  double number(const std::string& pointer) const {
    const json& v = at(pointer);
    require(v.is_number() && std::isfinite(v.get<double>()), pointer, "a number");
    return v.get<double>();
  }
  double number_or(const std::string& pointer, double otherwise) const {
    return has(pointer) ? number(pointer) : otherwise;
  }
  bool flag_or(const std::string& pointer, bool otherwise) const {
    if (!has(pointer)) return otherwise;
    const json& v = at(pointer);
    require(v.is_boolean(), pointer, "true or false");
    return v.get<bool>();
  }
  const json& object(const std::string& pointer) const {
    const json& v = at(pointer);
    require(v.is_object(), pointer, "an object");
    return v;
  }
  // Milliseconds, one per frame; with `nulls`, null for a frame not measured (NaN).
  std::vector<double> samples(const std::string& pointer, size_t frames, bool nulls = false) const {
    const json& values = at(pointer);
    require(values.is_array(), pointer, "an array of milliseconds");
    if (values.size() != frames)
      fail("\"" + dotted(pointer) + "\" has " + std::to_string(values.size()) + " values for " +
           std::to_string(frames) + " frames");
    std::vector<double> out;
    out.reserve(values.size());
    for (const json& v : values) {
      if (nulls && v.is_null()) {
        out.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      require(milliseconds(v), pointer, "finite, non-negative milliseconds");
      out.push_back(v.get<double>());
    }
    return out;
  }
  template <typename T>
  std::vector<T> array_of(const std::string& pointer, bool (*ok)(const json&), const char* expected) const {
    const json& values = at(pointer);
    require(values.is_array(), pointer, expected);
    std::vector<T> out;
    for (const json& v : values) {
      require(ok(v), pointer, expected);
      out.push_back(v.get<T>());
    }
    return out;
  }

 private:
  const json& doc_;
  const std::string& path_;
};

}  // namespace

std::string unreadable_format(int64_t format, const std::string& version) {
  if (format >= kOldestResultFormat && format <= kResultFormat) return "";
  return "result format " + std::to_string(format) + " (crowdprof " + version + "); this crowdprof reads formats " +
         std::to_string(kOldestResultFormat) + " to " + std::to_string(kResultFormat) +
         ": record it again with this version";
}

namespace {

void read_header(const Reader& in, const json& doc, Result& r) {
  if (!doc.is_object() || !doc.contains("crowdprof") || !doc["crowdprof"].is_object())
    in.fail("not a crowdprof result (no \"crowdprof\" section)");
  std::string kind = document_kind(doc);
  if (kind != "bench") in.fail("a '" + kind + "' result; check compares results of bench --json");
  if (!doc["crowdprof"].contains("format") || !doc["crowdprof"]["format"].is_number_integer())
    in.fail("not a crowdprof result (no \"crowdprof.format\")");
  int64_t format = doc["crowdprof"]["format"].get<int64_t>();
  const json& version = doc["crowdprof"].contains("version") ? doc["crowdprof"]["version"] : json();
  const std::string why = unreadable_format(format, version.is_string() ? version.get<std::string>() : "?");
  if (!why.empty()) in.fail(why);
  r.format = static_cast<int>(format);
  r.environment.version = in.text_or("/crowdprof/version", "?");
  r.environment.commit = in.text_or("/crowdprof/commit", "?");
}

void read_environment(const Reader& in, Result& r) {
  if (!in.has("/environment")) return;
  in.object("/environment");
  Environment& e = r.environment;
  e.cpu = in.text_or("/environment/cpu", "");
  e.cores = static_cast<unsigned>(std::min<uint64_t>(in.count_or("/environment/cores", 0), 1u << 20));
  e.compiler = in.text_or("/environment/compiler", "");
  e.build_type = in.text_or("/environment/build_type", "");
  e.simd = in.text_or("/environment/simd", "");
  e.fused_multiply_add = in.flag_or("/environment/fused_multiply_add", false);
  r.run.backend = in.text_or("/environment/backend", "none");
  r.run.renderer = in.text_or("/environment/renderer", "none");
}

// Sizes a scene records fit comfortably in these; larger ones are not results.
size_t bounded(uint64_t value, const Reader& in, const char* pointer) {
  in.require(value <= (uint64_t{1} << 40), pointer, "a plausible count");
  return static_cast<size_t>(value);
}

void read_scene(const Reader& in, Result& r) {
  RunDescription& run = r.run;
  in.object("/scene");
  run.file = in.text("/scene/file");
  in.text("/digest");  // checked here so a truncated result is named by its first missing field
  run.character = in.text("/scene/character");
  run.action_choice = in.text("/scene/action_choice");
  run.camera = in.text("/scene/camera");
  run.characters = bounded(in.count("/scene/characters"), in, "/scene/characters");
  run.joints = bounded(in.count("/scene/joints"), in, "/scene/joints");
  run.vertices = bounded(in.count("/scene/vertices"), in, "/scene/vertices");
  run.actions = bounded(in.count("/scene/actions"), in, "/scene/actions");
  uint64_t seed = in.count("/scene/seed");
  in.require(seed <= std::numeric_limits<uint32_t>::max(), "/scene/seed", "a 32-bit whole number");
  run.seed = static_cast<uint32_t>(seed);
  // Added within format 1: optional.
  run.action = in.text_or("/scene/action", "");
  run.resolution = in.text_or("/scene/resolution", "");
  run.scene_file = in.text_or("/scene/scene_file", "");
  run.scene_hash = in.text_or("/scene/scene_hash", "");
  r.file_from_result = in.text_or("/scene/file_from", "") == "result";
  if (in.has("/scene/lens") && !in.at("/scene/lens").is_null()) {
    in.object("/scene/lens");
    LensRecord lens;
    lens.focal_mm = in.number_or("/scene/lens/focal_mm", 0);
    lens.sensor_width_mm = in.number_or("/scene/lens/sensor_width_mm", 0);
    lens.sensor_height_mm = in.number_or("/scene/lens/sensor_height_mm", 0);
    lens.sensor_fit = in.text_or("/scene/lens/sensor_fit", "auto");
    run.lens = lens;
  }
}

void read_crowd(const Reader& in, Result& r) {
  if (!in.has("/crowd")) return;
  const json& crowd = in.at("/crowd");
  in.require(crowd.is_array(), "/crowd", "an array of characters");
  for (size_t k = 0; k < crowd.size(); ++k) {
    std::string at = "/crowd/" + std::to_string(k);
    in.object(at);
    CharacterRun c;
    c.file = in.text(at + "/file");
    c.character = in.text(at + "/character");
    c.content_hash = in.text_or(at + "/asset_hash", "");
    c.copies = bounded(in.count(at + "/copies"), in, "/crowd");
    c.joints = bounded(in.count(at + "/joints"), in, "/crowd");
    c.vertices = bounded(in.count(at + "/vertices"), in, "/crowd");
    c.actions = bounded(in.count(at + "/actions"), in, "/crowd");
    c.action_choice = in.text_or(at + "/action_choice", "");
    if (in.has(at + "/counters")) {
      in.object(at + "/counters");
      for (std::string_view name : kCharacterCounters)
        c.counters.*counter_field(name)->member = in.count_or(at + "/counters/" + std::string(name), 0);
    }
    r.run.crowd.push_back(std::move(c));
  }
}

void read_mode(const Reader& in, Result& r) {
  r.run.mode = in.text("/mode");
  const json& switches = in.object("/switches");
  // Switches added since the result was recorded hold the value runs had before;
  // one no run could have set is named as check names a bad baseline value.
  const std::string cannot = "records a run that crowdprof cannot make: ";
  for (const auto& [name, value] : switches.items()) {
    const SwitchSpec* spec = find_switch(name);
    if (!spec) in.fail(cannot + "no switch '" + name + "' (the switches are " + switch_names() + ")");
    std::string text = value.is_string() || value.is_boolean() || value.is_number() ? switch_text(value) : value.dump();
    if (std::string problem = spec->set(r.run.switches, text); !problem.empty())
      in.fail(cannot + name + " '" + text + "': " + problem);
  }
  uint64_t threads = in.count("/threads");
  if (threads > kMaxRecordedThreads)
    in.fail(cannot + "threads '" + std::to_string(threads) + "': expected at most " +
            std::to_string(kMaxRecordedThreads));
  r.run.threads = static_cast<int>(threads);
  r.run.warmup = bounded(in.count("/warmup"), in, "/warmup");
  r.run.fps = in.number("/fps");
  if (in.has("/gpu_skinning")) {
    in.object("/gpu_skinning");
    GpuSkinningRecord g;
    g.skinning = in.text_or("/gpu_skinning/skinning", "");
    g.gpu_bytes = in.count_or("/gpu_skinning/gpu_bytes", 0);
    if (in.has("/gpu_skinning/rate_hz")) {
      BakeRecord b;
      b.rate_hz = in.number("/gpu_skinning/rate_hz");
      b.samples = in.count_or("/gpu_skinning/samples", 0);
      b.bake_ms = in.number_or("/gpu_skinning/bake_ms", 0);
      b.max_deviation = in.number_or("/gpu_skinning/max_deviation", 0);
      b.max_deviation_fraction = in.number_or("/gpu_skinning/max_deviation_fraction", 0);
      g.bake = b;
    }
    r.run.gpu_skinning = g;
  }
  if (in.has("/gpu_memory")) {
    in.object("/gpu_memory");
    GpuMemoryRecord m;
    m.source = in.text("/gpu_memory/source");
    m.max_storage_block_bytes = in.count_or("/gpu_memory/max_storage_block_bytes", 0);
    for (auto [key, field] :
         {std::pair{"/gpu_memory/total_bytes", &m.total_bytes}, {"/gpu_memory/free_bytes", &m.free_bytes}})
      if (in.has(key) && !in.at(key).is_null()) *field = in.count(key);
    r.run.gpu_memory = m;
  }
}

// A category's key in "samples" (and "categories", "runs"): format 1 wrote
// the BGE's name ("GPU Latency"), format 2 the series' ("gpu_latency_ms").
std::string series_key(int format, Category category) {
  return format < 2 ? std::string(category_name(category)) : series_name(category);
}

// A format-1 metric key as format 2 names it ("Animations" -> "animations_ms").
std::string series_of_format1_key(const std::string& key) {
  for (size_t c = 0; c < kCategoryCount; ++c)
    if (key == category_name(static_cast<Category>(c))) return series_name(static_cast<Category>(c));
  return key;
}

// Per-pass GPU times (samples.gpu_<pass>_ms: a pass not drawn took none) and
// pipeline statistics (gpu_time.passes[].statistics), when written.
void read_gpu_passes(const Reader& in, Result& r, size_t frames) {
  bool split = false;
  for (size_t p = 0; p < kGpuPassCount; ++p) split |= in.has("/samples/" + pass_samples_key(p));
  if (!split) return;
  for (size_t p = 0; p < kGpuPassCount; ++p)
    r.samples.gpu_pass_ms[p] = in.has("/samples/" + pass_samples_key(p))
                                   ? in.samples("/samples/" + pass_samples_key(p), frames, true)
                                   : std::vector<double>(frames, 0.0);
  if (!in.has("/gpu_time/passes")) return;
  const json& passes = in.at("/gpu_time/passes");
  in.require(passes.is_array(), "/gpu_time/passes", "an array");
  for (size_t i = 0; i < passes.size(); ++i) {
    std::string at = "/gpu_time/passes/" + std::to_string(i);
    std::string name = in.text(at + "/pass");
    auto known = std::find(kGpuPassNames.begin(), kGpuPassNames.end(), name);
    if (known == kGpuPassNames.end()) in.fail("\"gpu_time.passes\" names no pass '" + name + "'");
    const auto pass = static_cast<size_t>(known - kGpuPassNames.begin());
    if (in.has(at + "/invocations_per_vertex_drawn")) {
      if (!r.invocations_per_vertex_drawn)
        r.invocations_per_vertex_drawn.emplace().fill(std::numeric_limits<double>::quiet_NaN());
      (*r.invocations_per_vertex_drawn)[pass] = in.number(at + "/invocations_per_vertex_drawn");
    }
    if (!in.has(at + "/statistics")) continue;
    in.object(at + "/statistics");
    auto& medians = r.pipeline_statistics ? *r.pipeline_statistics : r.pipeline_statistics.emplace();
    for (size_t s = 0; s < kPipelineStatCount; ++s)
      medians[pass][s] = static_cast<double>(in.count(at + "/statistics/" + std::string(kPipelineStatNames[s])));
  }
}

void read_samples(const Reader& in, Result& r) {
  uint64_t frames = in.count("/frames");
  if (frames == 0) in.fail("a result of 0 frames");
  in.object("/samples");
  ResultSamples& s = r.samples;
  s.frame_ms = in.samples("/samples/frame_ms", frames);
  // CPU time per frame arrived within format 1: read when present.
  if (in.has("/samples/cpu_ms")) s.cpu_ms = in.samples("/samples/cpu_ms", frames);
  // A calibrated run's probe (frame/calibration_probe.h); the ratio is derived
  // again, never trusted from the file.
  if (in.has("/samples/probe_ms")) {
    s.probe_ms = in.samples("/samples/probe_ms", frames);
    if (std::any_of(s.probe_ms.begin(), s.probe_ms.end(), [](double ms) { return !(ms > 0); }))
      in.fail("\"samples.probe_ms\" holds a time that is not above 0");
    s.calibrated = calibrated_frames(s.frame_ms, s.probe_ms);
    if (std::any_of(s.calibrated.begin(), s.calibrated.end(), [](double ratio) { return !std::isfinite(ratio); }))
      in.fail("\"samples.probe_ms\" holds a time too small to divide a frame by");
    r.calibration_probe = static_cast<int>(in.count("/calibration/probe"));
  }
  for (size_t c = 0; c < kCategoryCount; ++c)
    s.category_ms[c] = in.samples("/samples/" + series_key(r.format, static_cast<Category>(c)), frames);
  // The Animations split (2026-11-29): all four stages or none.
  if (in.has("/samples/" + animation_stage_series(0)))
    for (size_t st = 0; st < kAnimationStageCount; ++st)
      s.animation_stage_ms[st] = in.samples("/samples/" + animation_stage_series(st), frames);
  if (in.has("/samples/gpu_ms") && !in.at("/samples/gpu_ms").is_null())
    s.gpu_ms = in.samples("/samples/gpu_ms", frames, true);
  // No frame timed reads as not timed, as it is written.
  if (std::none_of(s.gpu_ms.begin(), s.gpu_ms.end(), [](double ms) { return std::isfinite(ms); })) s.gpu_ms.clear();
  r.run.gpu_timing_missing = "";  // "not recorded", unless gpu_time says why
  r.run.pipeline_statistics_missing = "";
  if (in.has("/gpu_time")) {
    in.object("/gpu_time");
    r.run.gpu_timing_missing = in.text_or("/gpu_time/reason", "");
    r.run.gpu_timer_resolution_ms = in.number_or("/gpu_time/resolution_ms", 0);
    r.run.pipeline_statistics_missing = in.text_or("/gpu_time/statistics_reason", "");
  }
  read_gpu_passes(in, r, frames);
}

void read_counters(const Reader& in, Result& r) {
  const json& counters = in.object("/counters");
  for (std::string_view name : kRequiredCounters) in.at("/counters/" + std::string(name));
  for (const auto& [name, value] : counters.items()) in.require(whole(value), "/counters/" + name, "a whole number");
  for (size_t i = 0; i < kCounterFields.size(); ++i) {
    std::string key(kCounterFields[i].name);
    if (!counters.contains(key)) continue;
    r.counters.values.*kCounterFields[i].member = counters[key].get<uint64_t>();
    r.counters.present[i] = true;
  }
}

// "runs" (check --runs): a count and one median per run for metrics of "samples".
void read_runs(const Reader& in, Result& r) {
  if (!in.has("/runs")) return;
  in.object("/runs");
  PooledRuns pool;
  pool.count = in.count("/runs/count");
  if (pool.count == 0 || pool.count > kMaxRuns) in.fail("\"runs.count\" should be 1 to " + std::to_string(kMaxRuns));
  const json& medians = in.object("/runs/median_ms");
  for (const auto& [written, values] : medians.items()) {
    std::string where = "/runs/median_ms/" + written;
    const std::string key = r.format < 2 ? series_of_format1_key(written) : written;
    if (!metric_samples(r, key)) in.fail("\"runs.median_ms." + written + "\" is not a metric of \"samples\"");
    in.require(values.is_array() && values.size() == pool.count, where, "an array of one median per run");
    pool.median_ms[key] = in.samples(where, pool.count);
  }
  auto is_integer = [](const json& v) { return v.is_number_integer(); };
  if (in.has("/runs/pids")) pool.pids = in.array_of<int64_t>("/runs/pids", is_integer, "an array of process ids");
  if (in.has("/runs/started_s"))
    pool.started_s = in.array_of<double>("/runs/started_s", milliseconds, "an array of seconds");
  r.runs = std::move(pool);
}

// An optional figure of bytes per copy on screen: absent in older results.
std::optional<double> bytes_per_copy(const Reader& in, const std::string& pointer) {
  if (!in.has(pointer)) return std::nullopt;
  const double bytes = in.number(pointer);
  in.require(bytes >= 0, pointer, "a number, 0 or more");
  return bytes;
}

void read_extras(const Reader& in, Result& r) {
  r.digest = in.text("/digest");
  r.digest_cpu_vertices = in.flag_or("/digest_cpu_vertices", true);
  const double scheme = in.number_or("/digest_scheme", 1);
  if (scheme != 1 && scheme != 2) in.fail("\"digest_scheme\" is " + std::to_string(scheme) + "; it should be 1 or 2");
  r.digest_scheme = static_cast<int>(scheme);
  r.vertex_order = in.text_or("/vertex_order", "file");
  if (r.vertex_order != "file" && r.vertex_order != "joints")
    in.fail("\"vertex_order\" is \"" + printable(r.vertex_order, 40) + "\"; it should be \"file\" or \"joints\"");
  r.stores = in.text_or("/stores", "");
  r.bytes_uploaded_per_copy_on_screen = bytes_per_copy(in, "/bytes_uploaded_per_copy_on_screen");
  r.palette_bytes_per_copy_on_screen = bytes_per_copy(in, "/palette_bytes_per_copy_on_screen");
  r.record_bytes_per_copy_on_screen = bytes_per_copy(in, "/record_bytes_per_copy_on_screen");
  r.partial = in.flag_or("/partial", false);
  r.frames_planned = r.partial ? bounded(in.count_or("/frames_planned", r.frames()), in, "/frames_planned") : 0;
  if (in.has("/animation")) {
    in.object("/animation");
    AnimationRecord a;
    auto is_whole = [](const json& v) { return whole(v); };
    a.copies_by_rate = in.array_of<uint64_t>("/animation/copies_by_rate", is_whole, "an array of copy counts");
    a.longest_gap_frames = in.count_or("/animation/longest_gap_frames", 0);
    a.budget_demotions = in.count_or("/animation/budget_demotions", 0);
    a.max_deviation = in.number_or("/animation/max_deviation", 0);
    a.deviation_fraction_of_height = in.number_or("/animation/deviation_fraction_of_height", 0);
    a.copies_checked = in.count_or("/animation/copies_checked", 0);
    a.copies_deviating = in.count_or("/animation/copies_deviating", 0);
    r.animation = std::move(a);
  }
  if (in.has("/mesh_lod")) {
    in.object("/mesh_lod");
    auto is_whole = [](const json& v) { return whole(v); };
    const auto copies = in.array_of<uint64_t>("/mesh_lod/copies", is_whole, "an array of copy counts");
    const auto error = in.array_of<double>("/mesh_lod/error", milliseconds, "an array of distances");
    const auto fraction = in.array_of<double>("/mesh_lod/error_fraction", milliseconds, "an array of fractions");
    const auto px = in.array_of<double>("/mesh_lod/error_px", milliseconds, "an array of pixels");
    const size_t levels = copies.size();
    in.require(levels >= 1 && levels <= 4 && error.size() == levels && fraction.size() == levels && px.size() == levels,
               "/mesh_lod", "arrays of one to four levels, all as long");
    MeshLodRecord m;
    for (size_t l = 0; l < levels; ++l) m.levels.push_back({copies[l], error[l], fraction[l], px[l]});
    r.mesh_lod = std::move(m);
  }
  if (in.has("/drawn_error")) {
    in.object("/drawn_error");
    DrawnErrorRecord e;
    e.copies_checked = in.count("/drawn_error/copies_checked");
    e.copies_deviating = in.count("/drawn_error/copies_deviating");
    e.vertices = in.count("/drawn_error/vertices");
    e.copy_stride = in.count("/drawn_error/copy_stride");
    in.require(e.copy_stride >= 1, "/drawn_error/copy_stride", "a whole number, 1 or more");
    in.require(e.copies_deviating <= e.copies_checked, "/drawn_error/copies_deviating",
               "a whole number, at most copies_checked");
    double* numbers[] = {&e.max,    &e.rms,    &e.max_fraction, &e.rms_fraction,
                         &e.max_px, &e.rms_px, &e.mesh_max,     &e.switches_per_second};
    const char* names[] = {"max",    "rms",    "max_fraction", "rms_fraction",
                           "max_px", "rms_px", "mesh_max",     "switches_per_second"};
    for (size_t n = 0; n < std::size(names); ++n) {
      const std::string at = std::string("/drawn_error/") + names[n];
      *numbers[n] = in.number(at);
      in.require(*numbers[n] >= 0, at, "a number, 0 or more");
    }
    r.drawn_error = std::move(e);
  }
  if (in.has("/culling_audit")) {
    in.object("/culling_audit");
    CullingAudit c;
    c.frames = in.count("/culling_audit/frames");
    c.copies = in.count("/culling_audit/copies");
    c.copy_stride = in.count("/culling_audit/copy_stride");
    c.in_view = in.count("/culling_audit/in_view");
    c.outside = in.count("/culling_audit/outside");
    c.undecided = in.count("/culling_audit/undecided");
    c.ms = in.number_or("/culling_audit/ms", 0.0);
    in.require(c.copy_stride >= 1, "/culling_audit/copy_stride", "a whole number, 1 or more");
    in.require(c.ms >= 0, "/culling_audit/ms", "a number, 0 or more");
    const json& boxes = in.object("/culling_audit/boxes");
    in.require(boxes.size() == kCullBoxes, "/culling_audit/boxes",
               "an object of bind_pose, every_action, own_action and tight");
    for (size_t k = 0; k < kCullBoxes; ++k) {
      const std::string name(cull_box_name(static_cast<CullBox>(k)));
      in.require(boxes.contains(name), "/culling_audit/boxes",
                 "an object of bind_pose, every_action, own_action and tight");
      const std::string at = "/culling_audit/boxes/" + name;
      in.object(at);
      CullBoxAudit& b = c.boxes[k];
      b.drawn = in.count(at + "/drawn");
      b.false_culls = in.count(at + "/false_culls");
      b.missed_culls = in.count(at + "/missed_culls");
      b.worst_frame_false_culls = in.count(at + "/worst_frame_false_culls");
      b.worst_frame_missed_culls = in.count(at + "/worst_frame_missed_culls");
      b.slack_mean = in.number(at + "/slack_mean");
      b.slack_max = in.number(at + "/slack_max");
    }
    r.culling_audit = std::move(c);
  }
  if (in.has("/instructions")) {
    in.object("/instructions");
    InstructionRecord i;
    i.source = in.text_or("/instructions/source", "");
    if (in.has("/instructions/per_frame") && !in.at("/instructions/per_frame").is_null())
      i.per_frame = in.number("/instructions/per_frame");
    i.threads = static_cast<int>(std::min<uint64_t>(in.count_or("/instructions/threads", 1), 4096));
    i.simd = in.text_or("/instructions/simd", "");
    i.compiler = in.text_or("/instructions/compiler", "");
    i.problem = in.text_or("/instructions/problem", "");
    if (in.has("/instructions/runs"))
      i.runs = in.array_of<double>("/instructions/runs", milliseconds, "an array of counts");
    i.frames = static_cast<size_t>(std::min<uint64_t>(in.count_or("/instructions/frames", 0), 1000000));
    i.warmup = static_cast<size_t>(std::min<uint64_t>(in.count_or("/instructions/warmup", 0), 1000000));
    r.instructions = std::move(i);
  }
  if (in.has("/pid")) {
    in.require(in.at("/pid").is_number_integer(), "/pid", "a process id");
    r.pid = in.at("/pid").get<int64_t>();
  }
  if (in.has("/started_s")) r.started_s = in.number("/started_s");
  if (in.has("/wall_s")) r.wall_s = in.number("/wall_s");
}

}  // namespace

Result result_from_json(const nlohmann::json& doc, const std::string& path) {
  Reader in(doc, path);
  Result r;
  read_header(in, doc, r);
  read_scene(in, r);
  read_mode(in, r);
  read_environment(in, r);
  read_crowd(in, r);
  read_samples(in, r);
  read_counters(in, r);
  read_extras(in, r);
  read_runs(in, r);
  return r;
}

}  // namespace crowdprof
