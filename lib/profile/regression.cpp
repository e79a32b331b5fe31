#include "profile/regression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "asset/errors.h"
#include "asset/input_file.h"
#include "frame/switch_table.h"
#include "profile/category_clock.h"
#include "profile/counters.h"
#include "profile/number_text.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// The counters every format-1 result has; later counters are compared when
// both results have them.
constexpr std::string_view kRequiredCounters[] = {"poses_updated",    "copies_culled",   "copies_visible",
                                                  "vertices_skinned", "channel_lookups", "bytes_uploaded",
                                                  "draw_calls"};

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string display_name(const std::string& key) {
  return key == "frame_ms" ? "frame" : key == "cpu_ms" ? "cpu" : key;
}

// "/scene/file" as users read it: "scene.file".
std::string dotted(const std::string& pointer) {
  std::string out = pointer.substr(1);
  std::replace(out.begin(), out.end(), '/', '.');
  return out;
}

std::string p_value(double p) {
  char text[32];
  std::snprintf(text, sizeof text, p < 1e-4 ? "%.1e" : "%.4f", p);
  return text;
}

// The value at a JSON pointer, or an InputError naming the field.
const json& field(const json& doc, const std::string& pointer, const std::string& path) {
  json::json_pointer at(pointer);
  if (!doc.contains(at)) throw InputError(path, "not a complete crowdprof result: no \"" + dotted(pointer) + "\"");
  return doc.at(at);
}

// Unsigned, or signed and not negative: nlohmann keeps the C++ type it was given.
bool whole(const json& value) {
  return value.is_number_unsigned() || (value.is_number_integer() && value.get<int64_t>() >= 0);
}

void require_type(bool ok, const std::string& pointer, const char* expected, const std::string& path) {
  if (!ok) throw InputError(path, "\"" + dotted(pointer) + "\" should be " + expected);
}

void validate_samples(const json& doc, const std::string& key, size_t frames, const std::string& path) {
  std::string where = "/samples/" + key;  // no key holds "~" or "/"
  const json& values = field(doc, where, path);
  require_type(values.is_array(), where, "an array of milliseconds", path);
  if (values.size() != frames)
    throw InputError(path, "\"samples." + key + "\" has " + std::to_string(values.size()) + " values for " +
                               std::to_string(frames) + " frames");
  for (const json& v : values)
    require_type(v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= 0, where,
                 "finite, non-negative milliseconds", path);
}

std::vector<double> samples_of(const json& doc, const std::string& key) {
  return doc.at("samples").at(key).get<std::vector<double>>();
}

// "runs" (pooled_runs): optional; when present, a count and one median per run
// for every samples key given, each a finite, non-negative number.
void validate_runs(const json& doc, const std::string& path) {
  if (!doc.contains("runs")) return;
  const json& runs = doc["runs"];
  require_type(runs.is_object(), "/runs", "an object", path);
  require_type(whole(field(doc, "/runs/count", path)), "/runs/count", "a whole number", path);
  size_t count = runs["count"].get<size_t>();
  if (count == 0 || count > kMaxRuns) throw InputError(path, "\"runs.count\" should be 1 to " + std::to_string(kMaxRuns));
  const json& medians = field(doc, "/runs/median_ms", path);
  require_type(medians.is_object(), "/runs/median_ms", "an object", path);
  for (const auto& [key, values] : medians.items()) {
    std::string where = "/runs/median_ms/" + key;
    if (!doc["samples"].contains(key) || !doc["samples"][key].is_array()) throw InputError(path, "\"runs.median_ms." + key + "\" is not a metric of \"samples\"");
    require_type(values.is_array() && values.size() == count, where, "an array of one median per run", path);
    for (const json& v : values)
      require_type(v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= 0, where,
                   "finite, non-negative milliseconds", path);
  }
}

// The medians of each run of `doc` for `key` when it pools `runs` or more runs
// (pooled_runs); empty otherwise.
std::vector<double> run_medians(const json& doc, const std::string& key, size_t runs) {
  if (!doc.contains("runs") || doc["runs"]["count"].get<size_t>() < runs || !doc["runs"]["median_ms"].contains(key))
    return {};
  return doc["runs"]["median_ms"][key].get<std::vector<double>>();
}

// A non-negative decimal number that is all of `s` (no sign, no words, finite).
bool parse_plain_number(const std::string& s, double& value) {
  size_t used = 0;
  if (s.empty() || !(std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '.')) return false;
  try {
    value = std::stod(s, &used);
  } catch (const std::exception&) {
    return false;
  }
  return used == s.size() && std::isfinite(value);
}

}  // namespace

double parse_tolerance(std::string_view text) {
  std::string s(text);
  bool is_percent = !s.empty() && s.back() == '%';
  if (is_percent) s.pop_back();
  double value = 0;
  if (!parse_plain_number(s, value))
    throw SettingError("tolerance", std::string(text), "expected a percentage such as 10% or a fraction such as 0.1");
  if (!is_percent && value >= 1)
    throw SettingError("tolerance", std::string(text),
                       "a fraction is below 1; for percent write " + std::string(text) + "%");
  if (is_percent) value /= 100.0;
  if (value > 10.0)
    throw SettingError("tolerance", std::string(text), "at most 1000%");
  return value;
}

Floor parse_floor(std::string_view text) {
  std::string s(text);
  auto bad = [&](const std::string& why) {
    return SettingError("floor", std::string(text), why);
  };
  double scale = 0;  // to ms; 0 for a percentage
  bool is_percent = false;
  for (auto [suffix, to_ms] : {std::pair<const char*, double>{"ms", 1.0}, {"us", 1e-3}, {"s", 1000.0}}) {
    std::string_view sv(s);
    if (sv.size() > std::strlen(suffix) && sv.ends_with(suffix)) {
      s.resize(s.size() - std::strlen(suffix));
      scale = to_ms;
      break;
    }
  }
  if (scale == 0 && !s.empty() && s.back() == '%') {
    s.pop_back();
    is_percent = true;
  }
  const char* expected = "expected a time such as 0.05ms or 50us, or a share of the baseline's median frame such as 2%";
  if (scale == 0 && !is_percent) throw bad(expected);
  double value = 0;
  if (!parse_plain_number(s, value)) throw bad(expected);
  Floor floor;
  if (is_percent) {
    if (value > 1000) throw bad("at most 1000%");
    floor.fraction_of_frame = value / 100.0;
  } else {
    if (value * scale > 3.6e6) throw bad("at most an hour");
    floor.fraction_of_frame = 0;
    floor.ms = value * scale;
  }
  return floor;
}

double floor_ms(const Floor& floor, double frame_ms) {
  return floor.fraction_of_frame > 0 ? floor.fraction_of_frame * frame_ms : floor.ms;
}

std::vector<std::string> all_metrics() {
  std::vector<std::string> keys = {"frame_ms"};
  for (size_t c = 0; c < kCategoryCount; ++c) keys.emplace_back(category_name(static_cast<Category>(c)));
  return keys;
}

std::string resolve_metric(std::string_view name) {
  std::string wanted = lower(name);
  if (wanted == "frame" || wanted == "frame_ms") return "frame_ms";
  if (wanted == "cpu" || wanted == "cpu_ms") return "cpu_ms";
  std::string choices = "frame, cpu";
  for (size_t c = 0; c < kCategoryCount; ++c) {
    auto category = static_cast<Category>(c);
    if (wanted == lower(category_name(category)) || wanted == category_column(category))
      return std::string(category_name(category));
    choices += ", " + std::string(category_name(category));
  }
  throw SettingError("metric", std::string(name), "expected one of " + choices);
}

nlohmann::json read_json_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw InputError(path, "no such file");
  if (fs::is_directory(status)) throw InputError(path, "a directory, not a crowdprof result");
  if (!fs::is_regular_file(status)) throw InputError(path, "not a regular file, so not a crowdprof result");
  // 10 million frames of eleven samples fit in well under this.
  constexpr uintmax_t kMaxResultBytes = uintmax_t{2} << 30;
  if (fs::file_size(path, error) > kMaxResultBytes) throw InputError(path, "larger than 2 GiB: not a crowdprof result");
  // A result is a JSON object: judged on the first bytes, before a large file
  // that is something else is read whole.
  std::string head = read_file_head(path);
  size_t first = head.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && head[first] != '{')
    throw InputError(path, "not a crowdprof result (not a JSON object)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot be read");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(path, "empty file, not a crowdprof result");
  return parse_json_input(path, text);
}

nlohmann::json read_result(const std::string& path) {
  json doc = read_json_file(path);
  validate_result(doc, path);
  return doc;
}

void validate_result(const nlohmann::json& doc, const std::string& path) {
  if (!doc.is_object() || !doc.contains("crowdprof") || !doc["crowdprof"].is_object())
    throw InputError(path, "not a crowdprof result (no \"crowdprof\" section)");
  const json& tag = doc["crowdprof"];
  auto text = [&](const char* key, const char* otherwise) {
    return tag.contains(key) && tag[key].is_string() ? tag[key].get<std::string>() : std::string(otherwise);
  };
  if (text("kind", "bench") != "bench")
    throw InputError(path, "a '" + text("kind", "") + "' result; check compares results of bench --json");
  if (!tag.contains("format") || !tag["format"].is_number_integer())
    throw InputError(path, "not a crowdprof result (no \"crowdprof.format\")");
  int64_t format = tag["format"].get<int64_t>();
  if (format != kResultFormat)
    throw InputError(path, "result format " + std::to_string(format) + " (crowdprof " + text("version", "?") +
                               "); this crowdprof reads format " + std::to_string(kResultFormat) +
                               ": record it again with this version");
  for (const char* key : {"/scene/file", "/scene/character", "/scene/action_choice", "/scene/camera", "/mode",
                          "/digest"})
    require_type(field(doc, key, path).is_string(), key, "a string", path);
  for (const char* key : {"/scene/characters", "/scene/joints", "/scene/vertices", "/scene/actions", "/scene/seed",
                          "/frames", "/warmup", "/threads"})
    require_type(whole(field(doc, key, path)), key, "a whole number", path);
  require_type(field(doc, "/fps", path).is_number(), "/fps", "a number", path);
  require_type(field(doc, "/switches", path).is_object(), "/switches", "an object", path);
  // Added within format 1: optional, but strings when present.
  for (const char* key : {"/scene/action", "/scene/resolution", "/environment/backend"})
    if (doc.contains(json::json_pointer(key))) require_type(doc.at(json::json_pointer(key)).is_string(), key, "a string", path);
  size_t frames = doc["frames"].get<size_t>();
  if (frames == 0) throw InputError(path, "a result of 0 frames");
  const json& samples = field(doc, "/samples", path);
  require_type(samples.is_object(), "/samples", "an object", path);
  validate_samples(doc, "frame_ms", frames, path);
  // CPU time per frame arrived within format 1: checked when present.
  if (samples.contains("cpu_ms")) validate_samples(doc, "cpu_ms", frames, path);
  for (size_t c = 0; c < kCategoryCount; ++c)
    validate_samples(doc, std::string(category_name(static_cast<Category>(c))), frames, path);
  const json& counters = field(doc, "/counters", path);
  require_type(counters.is_object(), "/counters", "an object", path);
  for (std::string_view name : kRequiredCounters)
    field(doc, std::string("/counters/").append(name), path);
  for (const auto& [name, value] : counters.items())
    require_type(whole(value), std::string("/counters/").append(name), "a whole number", path);
  validate_runs(doc, path);
}

void require_same_run(const nlohmann::json& baseline, const nlohmann::json& current, const std::string& path) {
  auto differ = [&](const std::string& what, const json& a, const json& b) {
    if (a == b) return;
    throw InputError(path, "the baseline is of another run: " + what + " " + a.dump() + " there, " + b.dump() +
                               " here (rerun with the baseline's options, or record it again with --update-baseline)");
  };
  auto file_name = [](const json& doc) {
    return std::filesystem::path(doc["scene"]["file"].get<std::string>()).filename().string();
  };
  differ("scene file", file_name(baseline), file_name(current));
  for (const char* key : {"character", "characters", "joints", "vertices", "actions", "action_choice", "camera"})
    differ(key, baseline["scene"][key], current["scene"][key]);
  if (current["scene"]["action_choice"] == "random") differ("seed", baseline["scene"]["seed"], current["scene"]["seed"]);
  for (const char* key : {"action", "resolution"})  // absent from results of early format-1 versions
    if (baseline["scene"].contains(key) && current["scene"].contains(key))
      differ(key, baseline["scene"][key], current["scene"][key]);
  // Drawing or not changes the work (bytes uploaded, draw calls); which GL
  // draws does not, and is only noted.
  auto backend = [](const json& doc) {
    bool known = doc.contains("environment") && doc["environment"].is_object();
    return known ? doc["environment"].value("backend", json("none")) : json("none");
  };
  if ((backend(baseline) == "none") != (backend(current) == "none"))
    differ("backend", backend(baseline), backend(current));
  differ("mode", baseline["mode"], current["mode"]);
  // Switches added since a baseline was recorded hold the value runs had
  // before; values are compared as the switches they set, not as text.
  auto switches = [](const json& recorded) {
    ModeSwitches s;
    return switches_from_json(recorded, s).empty() ? switches_to_json(s) : recorded;
  };
  differ("mode switches", switches(baseline["switches"]), switches(current["switches"]));
  for (const char* key : {"frames", "warmup", "fps"}) differ(key, baseline[key], current[key]);
}

namespace {
std::pair<std::string, std::string> split_skin(const std::string& file) {
  size_t hash = file.rfind("#skin=");
  return hash == std::string::npos ? std::pair{file, std::string()} : std::pair{file.substr(0, hash), file.substr(hash)};
}
}  // namespace

nlohmann::json with_paths_relative_to(nlohmann::json result, const std::string& result_path) {
  namespace fs = std::filesystem;
  fs::path folder = fs::absolute(fs::path(result_path)).parent_path();
  auto relocate = [&](json& scene) {
    if (!scene.is_object() || !scene.contains("file") || !scene["file"].is_string()) return;
    if (scene.value("file_from", json("")) == "result") return;
    auto [file, skin] = split_skin(scene["file"].get<std::string>());
    if (file.empty()) return;
    fs::path relative = fs::absolute(file).lexically_normal().lexically_relative(folder.lexically_normal());
    if (relative.empty()) return;
    scene["file"] = relative.string() + skin;
    scene["file_from"] = "result";
  };
  if (result.is_object() && result.contains("scene")) relocate(result["scene"]);
  if (result.is_object() && result.contains("runs") && result["runs"].is_array())
    for (json& run : result["runs"])
      if (run.is_object() && run.contains("scene")) relocate(run["scene"]);
  return result;
}

std::string recorded_scene_file(const nlohmann::json& result, const std::string& result_path) {
  namespace fs = std::filesystem;
  const json& scene = result["scene"];
  auto [file, skin] = split_skin(scene["file"].get<std::string>());
  fs::path folder = fs::path(result_path).parent_path();
  fs::path beside = (folder / file).lexically_normal();
  if (fs::path(file).is_absolute()) return file + skin;
  if (scene.value("file_from", json("")) == "result") return beside.string() + skin;
  std::error_code error;
  if (!fs::exists(file, error) && fs::exists(beside, error)) return beside.string() + skin;
  return file + skin;
}

std::vector<std::string> comparison_notes(const nlohmann::json& baseline, const nlohmann::json& current) {
  std::vector<std::string> notes;
  auto note = [&](const std::string& what, const json& a, const json& b) {
    if (a != b) notes.push_back("timings may not compare: " + what + " " + a.dump() + " in the baseline, " + b.dump() + " here");
  };
  note("threads", baseline["threads"], current["threads"]);
  const json none = "?";
  const json& be = baseline.contains("environment") && baseline["environment"].is_object() ? baseline["environment"] : json::object();
  const json& ce = current.contains("environment") && current["environment"].is_object() ? current["environment"] : json::object();
  note("backend", be.value("backend", none), ce.value("backend", none));
  // Another machine or build: one warning line naming every difference.
  std::string elsewhere;
  for (const char* key : {"cpu", "cores", "build_type", "compiler", "simd"}) {
    json a = be.value(key, none), b = ce.value(key, none);
    if (a != b && a != none) elsewhere += (elsewhere.empty() ? "" : "; ") + std::string(key) + " " + a.dump() + " there, " + b.dump() + " here";
  }
  if (!elsewhere.empty())
    notes.push_back("warning: the baseline was measured on another machine or build (" + elsewhere +
                    "): timings may not compare");
  // A scene file edited since the baseline: the counters or digest will say
  // whether the work changed; this says why.
  const json& bs = baseline["scene"];
  const json& cs = current["scene"];
  if (bs.contains("scene_hash") && cs.contains("scene_hash") && bs["scene_hash"] != cs["scene_hash"])
    notes.push_back("the scene file changed since the baseline: hash " + bs["scene_hash"].dump() + " then, " +
                    cs["scene_hash"].dump() + " now");
  return notes;
}

bool CheckResult::regressed() const {
  if (digest_differs() || !counters.empty() || !counters_missing.empty()) return true;
  return std::any_of(metrics.begin(), metrics.end(), [](const MetricCheck& m) { return m.regressed; });
}

namespace {

void decide(MetricCheck& m, const CheckOptions& options) {
  m.significant = m.p_adjusted < options.alpha && m.test.z > 0;
  m.regressed = m.beyond_tolerance && m.beyond_floor && (m.significant || m.too_few_samples);
}

}  // namespace

MetricCheck check_metric(std::string metric, std::span<const double> baseline, std::span<const double> current,
                         const CheckOptions& options, double floor) {
  MetricCheck m;
  m.metric = std::move(metric);
  m.baseline = summarize(baseline);
  m.current = summarize(current);
  m.baseline_iqr = quantile(baseline, 0.75) - quantile(baseline, 0.25);
  m.current_iqr = quantile(current, 0.75) - quantile(current, 0.25);
  double grew = m.current.median - m.baseline.median;
  m.change = m.baseline.median > 0 ? grew / m.baseline.median : (grew > 0 ? INFINITY : 0.0);
  m.test = mann_whitney(current, baseline);
  m.p_adjusted = m.test.p;
  m.floor_ms = floor;
  m.beyond_tolerance = m.change > options.tolerance;
  m.beyond_floor = grew > floor;
  m.too_few_samples = std::min(baseline.size(), current.size()) < kMannWhitneyMinSamples;
  decide(m, options);
  return m;
}

void adjust_holm(std::vector<MetricCheck>& metrics, const CheckOptions& options) {
  std::vector<size_t> order(metrics.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return metrics[a].test.p < metrics[b].test.p; });
  double running = 0;
  for (size_t k = 0; k < order.size(); ++k) {
    MetricCheck& m = metrics[order[k]];
    running = std::max(running, std::min(1.0, static_cast<double>(order.size() - k) * m.test.p));
    m.p_adjusted = running;
    decide(m, options);
  }
}

CheckResult check_results(const nlohmann::json& baseline, const nlohmann::json& current, const CheckOptions& options) {
  CheckResult result;
  // Runs are the unit when both results pool enough of them: processes differ
  // more than frames of one process do (child_run.h).
  std::vector<double> base_frame = run_medians(baseline, "frame_ms", kMannWhitneyMinSamples);
  double floor = floor_ms(options.floor, summarize(base_frame.empty() ? samples_of(baseline, "frame_ms") : base_frame).median);
  for (const std::string& key : options.metrics) {
    std::vector<double> a = run_medians(baseline, key, kMannWhitneyMinSamples);
    std::vector<double> b = run_medians(current, key, kMannWhitneyMinSamples);
    bool by_runs = !a.empty() && !b.empty();
    if (!by_runs) {
      a = samples_of(baseline, key);
      b = samples_of(current, key);
    }
    result.metrics.push_back(check_metric(display_name(key), a, b, options, floor));
    result.metrics.back().unit = by_runs ? "runs" : "frames";
  }
  adjust_holm(result.metrics, options);
  if (!options.compare_work) return result;
  const json& before = baseline["counters"];
  const json& after = current["counters"];
  for (const auto& [name, value] : before.items()) {
    if (!after.contains(name)) {
      result.counters_missing.push_back(name);
      continue;
    }
    uint64_t b = value.get<uint64_t>(), a = after[name].get<uint64_t>();
    if (a != b) result.counters.push_back({name, b, a});
  }
  result.baseline_digest = baseline["digest"].get<std::string>();
  result.current_digest = current["digest"].get<std::string>();
  return result;
}

std::string format_check(const CheckResult& result, const CheckOptions& options) {
  std::ostringstream out;
  double whole = std::round(options.tolerance * 100.0);
  std::string tolerance = fixed(options.tolerance * 100.0, std::abs(options.tolerance * 100.0 - whole) < 1e-9 ? 0 : 1) + "%";
  bool corrected = result.metrics.size() > 1;
  auto metric_line = [&](const MetricCheck& m, const char* verdict) {
    out << verdict << " " << m.metric << ": median " << fixed(m.baseline.median, 3) << " ms -> "
        << fixed(m.current.median, 3) << " ms (" << percent(m.change) << ", tolerance " << tolerance << ", floor "
        << fixed(m.floor_ms, 3) << " ms), IQR " << fixed(m.baseline_iqr, 3) << " -> " << fixed(m.current_iqr, 3)
        << " ms, p = " << p_value(m.test.p);
    if (corrected) out << " (Holm-corrected " << p_value(m.p_adjusted) << " over " << result.metrics.size() << " metrics)";
    out << " (Mann-Whitney U, " << m.test.n2 << " vs " << m.test.n1 << " " << m.unit
        << (m.unit == "runs" ? ", the median of each" : "")
        << (m.too_few_samples ? "; too few for the test, decided on the tolerance and floor" : "") << ")\n";
  };
  for (const MetricCheck& m : result.metrics)
    if (m.regressed) metric_line(m, "REGRESSION");
  for (const CounterDifference& d : result.counters)
    out << "CHANGED counter " << d.name << ": " << d.baseline << " -> " << d.current << " per frame\n";
  for (const std::string& name : result.counters_missing)
    out << "CHANGED counter " << name << ": in the baseline, missing here\n";
  if (result.digest_differs())
    out << "CHANGED digest: " << result.baseline_digest << " -> " << result.current_digest
        << " (the last frame's poses or skinned vertices differ)\n";
  if (result.regressed()) return out.str();
  // One line: every metric's verdict, then the exact checks.
  out << "ok";
  for (const MetricCheck& m : result.metrics) {
    out << " " << m.metric << " " << fixed(m.baseline.median, 3) << " -> " << fixed(m.current.median, 3) << " ms ("
        << percent(m.change) << ", p = " << p_value(m.p_adjusted);
    if (m.beyond_tolerance && !m.beyond_floor) out << ", beyond " << tolerance << " but under the floor of " << fixed(m.floor_ms, 3) << " ms";
    else if (m.beyond_tolerance) out << ", beyond " << tolerance << " but not significant";
    else if (m.change < -options.tolerance && m.p_adjusted < options.alpha) out << ", faster";
    else out << ", within " << tolerance;
    out << ");";
  }
  if (!result.metrics.empty())
    out << " " << result.metrics.front().test.n2 << " vs " << result.metrics.front().test.n1 << " "
        << result.metrics.front().unit << ";";
  out << (options.compare_work ? " counters and digest match\n" : " counters and digest not compared\n");
  return out.str();
}

}  // namespace crowdprof

namespace crowdprof {

json median_run(std::vector<json> runs, const std::string& key) {
  std::vector<std::pair<double, size_t>> medians;
  for (size_t i = 0; i < runs.size(); ++i) medians.emplace_back(summarize(samples_of(runs[i], key)).median, i);
  std::sort(medians.begin(), medians.end());
  return std::move(runs.at(medians.at((medians.size() - 1) / 2).second));
}

json pooled_runs(std::vector<json> runs, const std::string& key) {
  json medians = json::object();
  // Per-run fields moved into "runs" as arrays: "pid" to "pids", "started_s".
  std::pair<const char*, json> moved[] = {{"pid", json::array()}, {"started_s", json::array()}};
  for (json& run : runs) {
    for (const auto& [name, values] : run.at("samples").items())
      if (values.is_array())  // gpu_ms is null without a GPU timer
        medians[name].push_back(summarize(values.get<std::vector<double>>()).median);
    for (auto& [field, values] : moved)
      if (run.contains(field)) {
        values.push_back(run[field]);
        run.erase(field);
      }
  }
  size_t count = runs.size();
  json pooled = median_run(std::move(runs), key);
  pooled["runs"] = {{"count", count}, {"median_ms", std::move(medians)}};
  for (auto& [field, values] : moved)
    if (values.size() == count) pooled["runs"][std::string(field) == "pid" ? "pids" : field] = std::move(values);
  return pooled;
}

std::string metric_display_name(const std::string& key) { return display_name(key); }

}  // namespace crowdprof
