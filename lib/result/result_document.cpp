#include "result/result_document.h"

#include <cmath>
#include <stdexcept>
#include <string_view>
#include <tuple>

#include "base/errors.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// A row of a comparison's summary or sweep (or a capacity search's sweep),
// each field checked before use: mode, the axis and frame_median_ms are
// needed; the rest is read when present.
ModeMedians read_row(const json& row, SweepAxis axis, const std::string& path, const char* list) {
  const std::string key(to_string(axis));
  auto finite = [](const json& v) { return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= 0; };
  bool ok = row.is_object() && row.contains("mode") && row["mode"].is_string() && row.contains(key) &&
            row[key].is_number_unsigned() && row.contains("frame_median_ms") && finite(row["frame_median_ms"]);
  if (!ok) throw InputError(path, std::string("a \"") + list + "\" row without mode, " + key + " and frame_median_ms");
  auto bad = [&](const std::string& field) {
    return InputError(path, std::string("a \"") + list + "\" row whose \"" + field + "\" is not what crowdprof writes");
  };
  ModeMedians m;
  m.mode = row["mode"].get<std::string>();
  m.frame_ms = row["frame_median_ms"].get<double>();
  for (const char* whole : {"characters", "passes", "threads"}) {
    if (!row.contains(whole)) continue;
    const json& value = row[whole];
    const bool counted = value.is_number_unsigned() || (value.is_number_integer() && value.get<int64_t>() >= 0);
    if (!counted || value.get<uint64_t>() > (uint64_t{1} << 31)) throw bad(whole);
    const uint64_t v = value.get<uint64_t>();
    if (std::string_view(whole) == "characters")
      m.characters = static_cast<size_t>(v);
    else if (std::string_view(whole) == "passes")
      m.passes = static_cast<uint32_t>(v);
    else
      m.threads = static_cast<int>(v);
  }
  if (row.contains("speedup")) {
    if (!finite(row["speedup"])) throw bad("speedup");
    m.speedup = row["speedup"].get<double>();
  }
  if (row.contains("digest")) {
    if (!row["digest"].is_string()) throw bad("digest");
    m.digest = row["digest"].get<std::string>();
  }
  if (row.contains("categories_median_ms")) {
    const json& categories = row["categories_median_ms"];
    if (!categories.is_object()) throw bad("categories_median_ms");
    for (size_t k = 0; k < kCategoryCount; ++k) {
      const std::string name = series_name(static_cast<Category>(k));
      if (!categories.contains(name)) continue;
      if (!finite(categories[name])) throw bad("categories_median_ms." + name);
      m.category_ms[k] = categories[name].get<double>();
    }
  }
  if (row.contains("counters")) {
    const json& counters = row["counters"];
    if (!counters.is_object()) throw bad("counters");
    for (const CounterField& field : kCounterFields) {
      const std::string name(field.name);
      if (!counters.contains(name)) continue;
      if (!counters[name].is_number_unsigned()) throw bad("counters." + name);
      m.counters.*field.member = counters[name].get<uint64_t>();
    }
  }
  return m;
}

// The rows of `list` ("summary" or "sweep"), when the document has it.
std::vector<ModeMedians> read_rows(const json& doc, const char* list, SweepAxis axis, const std::string& path) {
  std::vector<ModeMedians> out;
  if (!doc.contains(list)) return out;
  const json& rows = doc[list];
  if (!rows.is_array()) throw InputError(path, std::string("\"") + list + "\" should be an array");
  for (const json& row : rows) out.push_back(read_row(row, axis, path, list));
  return out;
}

json row_json(const ModeMedians& m, bool with_passes) {
  json categories = json::object();
  for (size_t k = 0; k < kCategoryCount; ++k) categories[series_name(static_cast<Category>(k))] = m.category_ms[k];
  json j = {{"mode", m.mode},
            {"characters", m.characters},
            {"threads", m.threads},
            {"frame_median_ms", m.frame_ms},
            {"categories_median_ms", categories},
            {"speedup", m.speedup},
            {"digest", m.digest}};
  if (with_passes || m.passes != 1) j["passes"] = m.passes;
  for (const CounterField& field : kCounterFields) j["counters"][std::string(field.name)] = m.counters.*field.member;
  return j;
}

// A capacity result's search and outcome per mode, each field checked before use.
CapacityRecord read_capacity(const json& doc, const std::string& path) {
  auto bad = [&](const std::string& what) { return InputError(path, "a capacity result whose " + what); };
  auto number = [&](const json& v, const char* what) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
      throw bad(std::string(what) + " is not a non-negative number");
    return v.get<double>();
  };
  auto count = [&](const json& v, const char* what) {
    if (!v.is_number_unsigned() && !(v.is_number_integer() && v.get<int64_t>() >= 0))
      throw bad(std::string(what) + " is not a whole number");
    return v.get<size_t>();
  };
  CapacityRecord c;
  c.budget_ms = number(doc.value("budget_ms", json()), "\"budget_ms\"");
  const json metric = doc.value("metric", json());
  if (!metric.is_string()) throw bad("\"metric\" is not a string");
  c.metric = metric.get<std::string>();
  const json search = doc.value("search", json::object());
  if (!search.is_object()) throw bad("\"search\" is not an object");
  c.start = count(search.value("start", json(0)), "\"search.start\"");
  c.precision = number(search.value("resolution", json(0.0)), "\"search.resolution\"");
  c.frames_per_point = count(doc.value("frames_per_point", json(0)), "\"frames_per_point\"");
  c.warmup = count(doc.value("warmup_frames", json(0)), "\"warmup_frames\"");
  const json modes = doc.value("modes", json());
  if (!modes.is_array()) throw bad("\"modes\" is not an array");
  for (const json& m : modes) {
    if (!m.is_object() || !m.value("mode", json()).is_string()) throw bad("mode has no name");
    CapacityRecord::Row row;
    row.mode = m["mode"].get<std::string>();
    row.threads = count(m.value("threads", json(0)), "\"threads\"");
    row.cap = count(m.value("cap", json(0)), "\"cap\"");
    auto flag = [&](const char* key) {
      const json v = m.value(key, json(false));
      if (!v.is_boolean()) throw bad(std::string("\"") + key + "\" is not true or false");
      return v.get<bool>();
    };
    row.capped = flag("capped");
    row.non_monotonic = flag("non_monotonic");
    auto read_point = [&](const json& point) {
      if (!point.is_object()) throw bad("point is not an object");
      CapacityPoint p;
      p.n = count(point.value("characters", json()), "point's \"characters\"");
      p.median_ms = number(point.value("median_ms", json()), "point's \"median_ms\"");
      for (auto [key, ms] : {std::pair{"p95_ms", &p.p95_ms},
                             {"p99_ms", &p.p99_ms},
                             {"min_ms", &p.min_ms},
                             {"max_ms", &p.max_ms},
                             {"frame_median_ms", &p.frame_median_ms}})
        *ms = number(point.value(key, json(0.0)), key);
      p.frames = count(point.value("frames", json(0)), "point's \"frames\"");
      p.round = count(point.value("round", json(0)), "point's \"round\"");
      const json partial = point.value("partial", json(false)), digest = point.value("digest", json(""));
      if (!partial.is_boolean() || !digest.is_string())
        throw bad("point's \"partial\" or \"digest\" is of another type");
      p.partial = partial.get<bool>();
      p.digest = digest.get<std::string>();
      return p;
    };
    for (auto [key, slot] : {std::pair{"largest_fit", &row.fit}, {"first_over", &row.over}}) {
      const json point = m.value(key, json());
      if (point.is_null()) continue;
      if (!point.is_object()) throw bad(std::string("\"") + key + "\" is not a point");
      *slot = read_point(point);
    }
    const json points = m.value("points", json::array());
    if (!points.is_array()) throw bad("\"points\" is not an array");
    for (const json& point : points) row.points.push_back(read_point(point));
    c.rows.push_back(std::move(row));
  }
  return c;
}

// The document's "crowdprof.format", when it names one, as bench results'
// (result_codec.h): a format this crowdprof does not read is refused the same way.
void require_format(const json& doc, const std::string& path) {
  if (!doc.is_object() || !doc.contains("crowdprof") || !doc["crowdprof"].is_object()) return;
  const json& tag = doc["crowdprof"];
  if (!tag.contains("format")) return;
  if (!tag["format"].is_number_integer()) throw InputError(path, "\"crowdprof.format\" should be a whole number");
  const int64_t format = tag["format"].get<int64_t>();
  const json version = tag.value("version", json("?"));
  const std::string why = unreadable_format(format, version.is_string() ? version.get<std::string>() : "?");
  if (!why.empty()) throw InputError(path, why);
}

}  // namespace

ResultDocument result_document_from_json(const json& doc, const std::string& path) {
  ResultDocument out;
  require_format(doc, path);
  out.kind = document_kind(doc);
  if (out.kind == "ab_check")
    throw InputError(path,
                     "an A/B check of two builds (check --against --json): report reads results of bench, check "
                     "--baseline, compare, capacity and advise; the A/B's page is check --against BASE --html FILE");
  if (out.kind != "bench" && out.kind != "compare" && out.kind != "capacity" && out.kind != "advise")
    throw InputError(
        path, "a '" + out.kind + "' result; report reads results of bench, check, compare, capacity and advise --json");
  // A capacity search holds a comparison's runs (one per mode, at its
  // capacity) and sweep (every size it tried).
  out.runs = bench_results_in(doc, path);
  if (out.kind == "bench") return out;
  if (out.kind == "advise") {
    if (!doc.contains("advice")) throw InputError(path, "an advise result without \"advice\"");
    out.advice = advice_from_json(doc["advice"], path);
    out.partial = doc.contains("partial") && doc["partial"] == true;
    return out;
  }
  if (doc.contains("sweep_axis")) {
    if (doc["sweep_axis"] == "passes")
      out.sweep_axis = SweepAxis::Passes;
    else if (doc["sweep_axis"] != "characters")
      throw InputError(path, "\"sweep_axis\" should be characters or passes");
  }
  out.summary = read_rows(doc, "summary", SweepAxis::Characters, path);
  out.sweep = read_rows(doc, "sweep", out.sweep_axis, path);
  if (doc.contains("block_frames")) {
    if (!doc["block_frames"].is_number_unsigned()) throw InputError(path, "\"block_frames\" should be a whole number");
    out.block_frames = doc["block_frames"].get<size_t>();
  }
  out.partial = doc.contains("partial") && doc["partial"] == true;
  if (out.kind == "capacity") out.capacity = read_capacity(doc, path);
  return out;
}

ResultDocument read_result_document(const std::string& path) {
  return result_document_from_json(read_json_file(path), path);
}

namespace {

json point_json(const CapacityPoint& p, double budget_ms) {
  return {{"characters", p.n},
          {"median_ms", p.median_ms},
          {"p95_ms", p.p95_ms},
          {"p99_ms", p.p99_ms},
          {"min_ms", p.min_ms},
          {"max_ms", p.max_ms},
          {"frame_median_ms", p.frame_median_ms},
          {"frames", p.frames},
          {"fits", p.median_ms <= budget_ms},
          {"round", p.round},
          {"partial", p.partial},
          {"digest", p.digest}};
}

// The header of a search's document: the first run's build, machine and scene,
// without the crowd's size when the search varies it.
json search_header(const ResultDocument& d, const char* kind, bool keep_characters) {
  json j;
  const Result* head = d.described ? &*d.described : d.runs.empty() ? nullptr : &d.runs.front();
  if (head) {
    json first = result_to_json(*head);
    j["crowdprof"] = first["crowdprof"];
    j["environment"] = first["environment"];
    j["scene"] = first["scene"];
    if (!keep_characters) j["scene"].erase("characters");
  }
  j["crowdprof"]["kind"] = kind;
  return j;
}

json advise_json(const ResultDocument& d) {
  json j = search_header(d, "advise", true);
  j["partial"] = d.partial;
  j["advice"] = advice_to_json(*d.advice);
  j["runs"] = json::array();
  for (const Result& run : d.runs) j["runs"].push_back(result_to_json(run));
  return j;
}

json capacity_json(const ResultDocument& d) {
  const CapacityRecord& c = *d.capacity;
  json j = search_header(d, "capacity", false);  // each point has its own crowd size
  j["budget_ms"] = c.budget_ms;
  j["metric"] = c.metric;
  j["search"] = {{"start", c.start},
                 {"resolution", c.precision},
                 {"rule",
                  "doubling from start while the median fits, then bisection until first_over - largest_fit "
                  "<= max(1, floor(resolution * largest_fit))"}};
  j["block_frames"] = d.block_frames;
  j["frames_per_point"] = c.frames_per_point;
  j["warmup_frames"] = c.warmup;
  j["partial"] = d.partial;
  j["modes"] = json::array();
  for (const CapacityRecord::Row& row : c.rows) {
    json m = {{"mode", row.mode},
              {"threads", row.threads},
              {"cap", row.cap},
              {"capped", row.capped},
              {"non_monotonic", row.non_monotonic}};
    m["largest_fit"] = row.fit ? point_json(*row.fit, c.budget_ms) : json();
    m["first_over"] = row.over ? point_json(*row.over, c.budget_ms) : json();
    m["points"] = json::array();
    for (const CapacityPoint& p : row.points) m["points"].push_back(point_json(p, c.budget_ms));
    j["modes"].push_back(m);
  }
  j["sweep"] = json::array();
  for (const ModeMedians& s : d.sweep)
    j["sweep"].push_back({{"mode", s.mode}, {"characters", s.characters}, {"frame_median_ms", s.frame_ms}});
  j["runs"] = json::array();
  for (const Result& run : d.runs) j["runs"].push_back(result_to_json(run));
  return j;
}

}  // namespace

json result_document_to_json(const ResultDocument& d) {
  if (d.kind == "bench") return d.runs.empty() ? json::object() : result_to_json(d.runs.front());
  if (d.kind == "capacity" && d.capacity) return capacity_json(d);
  if (d.kind == "advise" && d.advice) return advise_json(d);
  if (d.kind != "compare") throw std::logic_error("result_document_to_json: a '" + d.kind + "' document");
  json j;
  json runs = json::array(), summary = json::array(), sweep = json::array(), modes = json::array();
  for (const Result& run : d.runs) runs.push_back(result_to_json(run));
  for (const ModeMedians& m : d.summary) {
    summary.push_back(row_json(m, false));
    modes.push_back(m.mode);
  }
  for (const ModeMedians& m : d.sweep) sweep.push_back(row_json(m, d.sweep_axis == SweepAxis::Passes));
  if (!runs.empty()) {
    j["crowdprof"] = runs[0]["crowdprof"];
    j["environment"] = runs[0]["environment"];
    j["scene"] = runs[0]["scene"];
  }
  j["crowdprof"]["kind"] = d.kind;
  if (d.partial) j["partial"] = true;
  j["block_frames"] = d.block_frames;
  if (!modes.empty()) j["modes"] = modes;
  j["summary"] = summary;
  j["sweep"] = sweep;
  if (d.sweep_axis != SweepAxis::Characters) j["sweep_axis"] = to_string(d.sweep_axis);
  j["runs"] = runs;
  return j;
}

json diff_record_to_json(const DiffRecord& d) {
  json j;
  j["crowdprof"] = {{"version", d.version}, {"commit", d.commit}, {"kind", "diff"}, {"format", kResultFormat}};
  j["a"] = d.a;
  j["b"] = d.b;
  j["tolerance"] = d.tolerance;
  j["alpha"] = d.alpha;
  j["pairs"] = json::array();
  auto optional = [](const auto& value) { return value ? json(*value) : json(nullptr); };
  for (const DiffRecord::Pair& pair : d.pairs) {
    json p = {
        {"mode", pair.mode}, {"characters", pair.characters}, {"regressed", pair.regressed}, {"notes", pair.notes}};
    p["metrics"] = json::array();
    for (const DiffRecord::Metric& m : pair.metrics)
      p["metrics"].push_back({{"metric", m.metric},
                              {"a_median_ms", m.a_median},
                              {"b_median_ms", m.b_median},
                              {"unit", m.unit},
                              {"change", optional(m.change)},
                              {"p", optional(m.p)},
                              {"p_holm", optional(m.p_holm)},
                              {"tested", m.tested},
                              {"floor_ms", m.floor_ms},
                              {"verdict", m.verdict}});
    p["counters"] = json::array();
    for (const DiffRecord::Counter& counter : pair.counters)
      p["counters"].push_back({{"name", counter.name}, {"a", optional(counter.a)}, {"b", optional(counter.b)}});
    p["digest"] = {{"a", pair.digest_a}, {"b", pair.digest_b}, {"same", pair.digest_a == pair.digest_b}};
    if (!pair.digest_note.empty()) p["digest"]["note"] = pair.digest_note;
    j["pairs"].push_back(p);
  }
  j["regressed"] = d.regressed;
  return j;
}

DiffRecord diff_record_from_json(const json& doc, const std::string& path) {
  auto bad = [&](const std::string& field, const char* should) {
    return InputError(path, "\"" + field + "\" should be " + should);
  };
  auto object = [&](const json& parent, const std::string& key, const std::string& at) -> const json& {
    if (!parent.contains(key) || !parent[key].is_object()) throw bad(at, "an object");
    return parent[key];
  };
  auto array = [&](const json& parent, const std::string& key, const std::string& at) -> const json& {
    if (!parent.contains(key) || !parent[key].is_array()) throw bad(at, "an array");
    return parent[key];
  };
  auto text = [&](const json& parent, const std::string& key, const std::string& at) {
    if (!parent.contains(key) || !parent[key].is_string()) throw bad(at, "a string");
    return parent[key].get<std::string>();
  };
  auto flag = [&](const json& parent, const std::string& key, const std::string& at) {
    if (!parent.contains(key) || !parent[key].is_boolean()) throw bad(at, "true or false");
    return parent[key].get<bool>();
  };
  auto number = [&](const json& parent, const std::string& key, const std::string& at) {
    if (!parent.contains(key) || !parent[key].is_number() || !std::isfinite(parent[key].get<double>()))
      throw bad(at, "a number");
    return parent[key].get<double>();
  };
  auto maybe_number = [&](const json& parent, const std::string& key, const std::string& at) -> std::optional<double> {
    if (parent.contains(key) && parent[key].is_null()) return std::nullopt;
    return number(parent, key, at);
  };
  auto whole = [&](const json& v) {
    return v.is_number_unsigned() || (v.is_number_integer() && v.get<int64_t>() >= 0);
  };
  require_format(doc, path);
  if (document_kind(doc) != "diff")
    throw InputError(path, "not a crowdprof diff (its \"crowdprof.kind\" is not \"diff\")");
  DiffRecord d;
  const json& tag = object(doc, "crowdprof", "crowdprof");
  d.version = text(tag, "version", "crowdprof.version");
  d.commit = text(tag, "commit", "crowdprof.commit");
  d.a = text(doc, "a", "a");
  d.b = text(doc, "b", "b");
  d.tolerance = number(doc, "tolerance", "tolerance");
  d.alpha = number(doc, "alpha", "alpha");
  d.regressed = flag(doc, "regressed", "regressed");
  const json& pairs = array(doc, "pairs", "pairs");
  for (size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = "pairs[" + std::to_string(i) + "]";
    if (!pairs[i].is_object()) throw bad(at, "an object");
    const json& p = pairs[i];
    DiffRecord::Pair pair;
    pair.mode = text(p, "mode", at + ".mode");
    if (!p.contains("characters") || !whole(p["characters"])) throw bad(at + ".characters", "a whole number");
    pair.characters = p["characters"].get<size_t>();
    pair.regressed = flag(p, "regressed", at + ".regressed");
    for (const json& note : array(p, "notes", at + ".notes")) {
      if (!note.is_string()) throw bad(at + ".notes", "an array of strings");
      pair.notes.push_back(note.get<std::string>());
    }
    const json& metrics = array(p, "metrics", at + ".metrics");
    for (size_t k = 0; k < metrics.size(); ++k) {
      const std::string mat = at + ".metrics[" + std::to_string(k) + "]";
      if (!metrics[k].is_object()) throw bad(mat, "an object");
      const json& m = metrics[k];
      DiffRecord::Metric metric;
      metric.metric = text(m, "metric", mat + ".metric");
      metric.unit = text(m, "unit", mat + ".unit");
      metric.verdict = text(m, "verdict", mat + ".verdict");
      metric.a_median = number(m, "a_median_ms", mat + ".a_median_ms");
      metric.b_median = number(m, "b_median_ms", mat + ".b_median_ms");
      metric.floor_ms = number(m, "floor_ms", mat + ".floor_ms");
      metric.change = maybe_number(m, "change", mat + ".change");
      metric.p = maybe_number(m, "p", mat + ".p");
      metric.p_holm = maybe_number(m, "p_holm", mat + ".p_holm");
      metric.tested = flag(m, "tested", mat + ".tested");
      pair.metrics.push_back(std::move(metric));
    }
    for (const json& c : array(p, "counters", at + ".counters")) {
      if (!c.is_object()) throw bad(at + ".counters", "an array of objects");
      DiffRecord::Counter counter;
      counter.name = text(c, "name", at + ".counters.name");
      for (auto [key, slot] : {std::pair{"a", &counter.a}, {"b", &counter.b}}) {
        if (!c.contains(key)) throw bad(at + ".counters." + key, "a whole number or null");
        if (c[key].is_null()) continue;
        if (!c[key].is_number_unsigned()) throw bad(at + ".counters." + key, "a whole number or null");
        *slot = c[key].get<uint64_t>();
      }
      pair.counters.push_back(std::move(counter));
    }
    const json& digest = object(p, "digest", at + ".digest");
    pair.digest_a = text(digest, "a", at + ".digest.a");
    pair.digest_b = text(digest, "b", at + ".digest.b");
    if (digest.contains("note")) pair.digest_note = text(digest, "note", at + ".digest.note");
    d.pairs.push_back(std::move(pair));
  }
  return d;
}

}  // namespace crowdprof
