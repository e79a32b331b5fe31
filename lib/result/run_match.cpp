#include "result/run_match.h"

#include <filesystem>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "base/switch_table.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// As a user reads a value in a message: strings quoted, numbers bare.
template <typename T>
std::string shown(const T& value) {
  return json(value).dump();
}

}  // namespace

std::vector<RunDifference> run_differences(const Result& baseline, const Result& current) {
  std::vector<RunDifference> out;
  auto differ = [&](const std::string& what, const std::string& a, const std::string& b) {
    if (a != b) out.push_back({what, a, b});
  };
  const RunDescription& b = baseline.run;
  const RunDescription& c = current.run;
  auto file_name = [](const RunDescription& run) { return std::filesystem::path(run.file).filename().string(); };
  differ("scene file", shown(file_name(b)), shown(file_name(c)));
  differ("character", shown(b.character), shown(c.character));
  differ("characters", shown(b.characters), shown(c.characters));
  differ("joints", shown(b.joints), shown(c.joints));
  differ("vertices", shown(b.vertices), shown(c.vertices));
  differ("actions", shown(b.actions), shown(c.actions));
  differ("action_choice", shown(b.action_choice), shown(c.action_choice));
  differ("camera", shown(b.camera), shown(c.camera));
  if (c.action_choice == "random") differ("seed", shown(b.seed), shown(c.seed));
  // Absent ("") from results of early format-1 versions.
  if (!b.action.empty() && !c.action.empty()) differ("action", shown(b.action), shown(c.action));
  if (!b.resolution.empty() && !c.resolution.empty()) differ("resolution", shown(b.resolution), shown(c.resolution));
  // Drawing or not changes the work (bytes uploaded, draw calls); which GL
  // draws does not, and is only noted.
  if ((b.backend == "none") != (c.backend == "none")) differ("backend", shown(b.backend), shown(c.backend));
  differ("mode", shown(b.mode), shown(c.mode));
  // Switches added since a baseline was recorded read as the value runs had
  // before (result_codec), so they are compared as the switches they set.
  // The order of the GPU's triangles is no work when nothing is drawn: an A/B
  // against a build from before the switch (file order) is of the same run.
  ModeSwitches bs = b.switches, cs = c.switches;
  if (b.backend == "none" && c.backend == "none") bs.index_order = cs.index_order;
  // Only the switches that differ, in the table's order, as users type them.
  const auto [switches_b, switches_c] = switch_differences(bs, cs);
  differ("mode switches", switches_b, switches_c);
  differ("frames", shown(baseline.frames()), shown(current.frames()));
  differ("warmup", shown(b.warmup), shown(c.warmup));
  differ("fps", shown(b.fps), shown(c.fps));
  return out;
}

void require_same_run(const Result& baseline, const Result& current, const std::string& path) {
  const std::vector<RunDifference> differences = run_differences(baseline, current);
  if (differences.empty()) return;
  const RunDifference& d = differences.front();
  throw SettingsInputError(path, "the baseline is of another run: " + d.field + " " + d.a + " there, " + d.b + " here ",
                           "(rerun with the baseline's options, or record it again with {update_baseline})");
}

std::vector<std::string> comparison_notes(const Result& baseline, const Result& current) {
  std::vector<std::string> notes;
  auto note = [&](const std::string& what, const std::string& a, const std::string& b) {
    if (a != b) notes.push_back("timings may not compare: " + what + " " + a + " in the baseline, " + b + " here");
  };
  note("threads", shown(baseline.run.threads), shown(current.run.threads));
  note("backend", shown(baseline.run.backend), shown(current.run.backend));
  // Another machine or build: one warning line naming every difference. A
  // field the baseline did not record ("") is not a difference.
  const Environment& be = baseline.environment;
  const Environment& ce = current.environment;
  std::string elsewhere;
  auto compare = [&](const char* key, const std::string& a, const std::string& b) {
    if (a != b && a != shown(std::string()))
      elsewhere += (elsewhere.empty() ? "" : "; ") + std::string(key) + " " + a + " there, " + b + " here";
  };
  compare("cpu", shown(be.cpu), shown(ce.cpu));
  if (be.cores != 0 && be.cores != ce.cores) compare("cores", shown(be.cores), shown(ce.cores));
  compare("build_type", shown(be.build_type), shown(ce.build_type));
  compare("compiler", shown(be.compiler), shown(ce.compiler));
  compare("simd", shown(be.simd), shown(ce.simd));
  if (!elsewhere.empty())
    notes.push_back("warning: the baseline was measured on another machine or build (" + elsewhere +
                    "): timings may not compare");
  // A scene file edited since the baseline: the counters or digest will say
  // whether the work changed; this says why.
  const std::string& bh = baseline.run.scene_hash;
  const std::string& ch = current.run.scene_hash;
  if (!bh.empty() && !ch.empty() && bh != ch)
    notes.push_back("the scene file changed since the baseline: hash " + shown(bh) + " then, " + shown(ch) + " now");
  return notes;
}

}  // namespace crowdprof
