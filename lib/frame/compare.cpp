#include "frame/compare.h"

#include <algorithm>
#include <sstream>

#include "base/errors.h"
#include "base/switch_table.h"
#include "frame/bench_setup.h"

namespace crowdprof {

void check_fits_in_memory(const Character& character, std::span<const BenchConfig> configs) {
  const Character* one[] = {&character};
  check_fits_in_memory(one, configs);
}

void check_fits_in_memory(std::span<const Character* const> characters, std::span<const BenchConfig> configs) {
  uint64_t needed = 0;
  for (const BenchConfig& config : configs) needed += estimate_bench_bytes(characters, config.crowd, config.mode);
  uint64_t available = available_memory_bytes();
  if (available == 0 || needed <= available * 9 / 10) return;
  auto mib = [](uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; };
  throw UsageError(std::to_string(configs.size()) + " modes of this crowd side by side need about " + mib(needed) +
                   " of memory; this machine has " + mib(available) + " available (compare fewer modes or copies)");
}

size_t largest_crowd_in_memory(std::span<const Character* const> characters, BenchConfig config, size_t cap,
                               size_t side_by_side) {
  uint64_t available = available_memory_bytes();
  if (available == 0) return cap;
  uint64_t share = available * 9 / 10 / std::max<size_t>(side_by_side, 1);
  auto fits = [&](size_t n) {
    config.crowd.copies = n;
    return estimate_bench_bytes(characters, config.crowd, config.mode) <= share;
  };
  if (fits(cap)) return cap;
  size_t lo = 0, hi = cap;  // fits(lo) (or lo = 0), !fits(hi)
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

std::vector<Result> run_interleaved(std::span<CrowdBench* const> benches, const std::string& file,
                                    const RunOptions& options, size_t block) {
  block = std::max<size_t>(block, 1);
  std::vector<Result> reports(benches.size());
  Environment environment = current_environment();
  for (size_t b = 0; b < benches.size(); ++b) {
    reports[b].run = describe_run(*benches[b], file);
    reports[b].run.warmup = options.warmup;
    reports[b].environment = environment;
    reports[b].frame_records.reserve(options.frames);
    reports[b].frames_planned = options.frames;
  }
  size_t per_bench = options.warmup + options.frames;
  size_t total = per_bench * benches.size(), done = 0;
  for (size_t start = 0; start < per_bench; start += block) {
    size_t end = std::min(per_bench, start + block);
    if (options.stop && options.stop->load()) {
      // Stopped between rounds: every mode has the same frames so far.
      for (Result& report : reports) report.partial = true;
      break;
    }
    for (size_t b = 0; b < benches.size(); ++b) {
      // The other benches' blocks are not this bench's time.
      benches[b]->restart_clock();
      for (size_t i = start; i < end; ++i) {
        FrameRecord record = benches[b]->step();
        if (i >= options.warmup) reports[b].frame_records.push_back(record);
        place_gpu_times(*benches[b], options.warmup, reports[b].frame_records);
        if (options.progress) options.progress(++done, total);
      }
      // The block's last frames: their timer queries are done before the next
      // mode draws (with one renderer for all modes, its queries are shared).
      benches[b]->collect_gpu_times();
      place_gpu_times(*benches[b], options.warmup, reports[b].frame_records);
    }
  }
  for (size_t b = 0; b < benches.size(); ++b) {
    // Every mode culls the same crowd from the same camera: one audit serves all.
    finish_run(*benches[b], reports[b], b == 0);
    if (b > 0) reports[b].culling_audit = reports[0].culling_audit;
  }
  return reports;
}

Sweep parse_sweep(const std::string& text) {
  Sweep sweep;
  std::string list = text;
  if (text.rfind("n=", 0) == 0) {
    list = text.substr(2);
  } else if (text.rfind("passes=", 0) == 0) {
    sweep.axis = SweepAxis::Passes;
    list = text.substr(7);
  }
  const bool passes = sweep.axis == SweepAxis::Passes;
  const char* expected = passes ? "expected passes such as passes=1,2,4,6"
                                : "expected crowd sizes such as n=10,20,40,80,160, or passes=1,2,4,6";
  std::stringstream in(list);
  std::string item;
  auto bad = [&](const std::string& why) { return UsageError("--sweep '" + text + "': " + why); };
  while (std::getline(in, item, ',')) {
    if (item.empty() || item.size() > 8 || item.find_first_not_of("0123456789") != std::string::npos)
      throw bad(expected);
    size_t n = std::stoul(item);
    if (passes && (n < 1 || n > kMaxPasses))
      throw bad("each count of passes must be 1 to " + std::to_string(kMaxPasses));
    if (!passes && (n < 1 || n > 10'000'000)) throw bad("each size must be 1 to 10,000,000");
    if (std::find(sweep.points.begin(), sweep.points.end(), n) == sweep.points.end()) sweep.points.push_back(n);
  }
  if (sweep.points.empty()) throw bad(expected);
  std::sort(sweep.points.begin(), sweep.points.end());
  return sweep;
}

namespace {
// The fields of a layer after its first (base/anim_layers.h).
constexpr const char* kLayerFields[] = {"action=", "mask=", "weight=", "falloff=", "blend="};
}  // namespace

std::string apply_mode_spec(const std::string& spec, RunSpec& run) {
  std::string preset = spec.substr(0, spec.find('+'));
  if (!find_mode(preset)) throw UsageError("--modes '" + spec + "': expected some of " + mode_names());
  size_t at = preset.size();
  while (at < spec.size()) {
    size_t next = spec.find('+', at + 1);
    std::string item = spec.substr(at + 1, next == std::string::npos ? std::string::npos : next - at - 1);
    size_t equals = item.find('=');
    std::string key = item.substr(0, equals);
    for (char& c : key)
      if (c == '-') c = '_';  // share-quantum as the option spells it, share_quantum as results do
    if (!find_switch(key) || equals == std::string::npos || equals + 1 == item.size())
      throw UsageError("--modes '" + spec + "': '" + item + "': expected SWITCH=VALUE with a switch of " +
                       switch_names());
    std::string value = item.substr(equals + 1);
    ModeSwitches scratch;
    if (std::string problem = find_switch(key)->set(scratch, value); !problem.empty())
      throw UsageError("--modes '" + spec + "': " + key + " '" + value + "': " + problem);
    run.switches[key] = value;
    at = next == std::string::npos ? spec.size() : next;
  }
  return preset;
}

BenchConfig config_for(const RunSpec& shared, const std::string& mode, const BenchScene& scene) {
  RunSpec spec = shared;
  spec.mode = apply_mode_spec(mode, spec);
  if (!spec.mode_switches().parallel) spec.threads = 0;
  BenchConfig config = make_bench_config(spec, scene);
  if (mode.find('+') != std::string::npos) config.mode_name = mode;  // as the user named it
  return config;
}

std::vector<std::string> modes_to_run(const std::vector<std::string>& asked) {
  // The list came split at every comma; a layer's fields (anim_layer=action=
  // wave,mask=spine) go back to the mode they belong to.
  std::vector<std::string> names;
  for (const std::string& piece : asked) {
    const bool field = !names.empty() &&
                       (names.back().find("anim_layer=") != std::string::npos ||
                        names.back().find("anim-layer=") != std::string::npos) &&
                       std::any_of(std::begin(kLayerFields), std::end(kLayerFields),
                                   [&](const char* key) { return piece.rfind(key, 0) == 0; });
    if (field)
      names.back() += "," + piece;
    else
      names.push_back(piece);
  }
  if (names.empty())
    for (const ModePreset& preset : mode_presets()) names.emplace_back(preset.name);
  for (size_t i = 0; i < names.size(); ++i) {
    RunSpec scratch;
    apply_mode_spec(names[i], scratch);  // throws on a bad name or switch
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), names[i]) !=
        names.begin() + static_cast<std::ptrdiff_t>(i))
      throw UsageError("--modes: " + names[i] + " is listed twice");
  }
  return names;
}

void check_block(long long block) {
  if (block < 1 || block > 1'000'000) throw UsageError("--block " + std::to_string(block) + ": expected 1 to 1000000");
}

}  // namespace crowdprof
