#include "result/result_document.h"

#include <cmath>
#include <tuple>

#include "base/errors.h"
#include "result/result_codec.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// A comparison's sweep rows, each field checked before use.
void read_sweep(ResultDocument& out, const json& doc, const std::string& path) {
  if (!doc.contains("sweep")) return;
  const json& sweep = doc["sweep"];
  if (!sweep.is_array()) throw InputError(path, "\"sweep\" should be an array");
  if (doc.contains("sweep_axis")) {
    if (doc["sweep_axis"] == "passes") out.sweep_axis = SweepAxis::Passes;
    else if (doc["sweep_axis"] != "characters") throw InputError(path, "\"sweep_axis\" should be characters or passes");
  }
  std::string axis(to_string(out.sweep_axis));
  for (const json& row : sweep) {
    bool ok = row.is_object() && row.contains("mode") && row["mode"].is_string() && row.contains(axis) &&
              row[axis].is_number_unsigned() && row.contains("frame_median_ms") &&
              row["frame_median_ms"].is_number() && std::isfinite(row["frame_median_ms"].get<double>()) &&
              row["frame_median_ms"].get<double>() >= 0;
    if (!ok) throw InputError(path, "a \"sweep\" row without mode, " + axis + " and frame_median_ms");
    out.sweep.push_back({row["mode"].get<std::string>(), row[axis].get<size_t>(), row["frame_median_ms"].get<double>()});
  }
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
    for (auto [key, n, ms] : {std::tuple{"largest_fit", &row.fits, &row.fits_ms}, {"first_over", &row.over, &row.over_ms}}) {
      const json point = m.value(key, json());
      if (point.is_null()) continue;
      if (!point.is_object()) throw bad(std::string("\"") + key + "\" is not a point");
      *n = count(point.value("characters", json()), "point's \"characters\"");
      *ms = number(point.value("median_ms", json()), "point's \"median_ms\"");
    }
    c.rows.push_back(std::move(row));
  }
  return c;
}

}  // namespace

ResultDocument result_document_from_json(const json& doc, const std::string& path) {
  ResultDocument out;
  out.kind = document_kind(doc);
  if (out.kind != "bench" && out.kind != "compare" && out.kind != "capacity")
    throw InputError(path, "a '" + out.kind + "' result; report reads results of bench, check, compare and capacity --json");
  // A capacity search holds a comparison's runs (one per mode, at its
  // capacity) and sweep (every size it tried).
  out.runs = bench_results_in(doc, path);
  if (out.kind == "bench") return out;
  read_sweep(out, doc, path);
  if (out.kind == "capacity") out.capacity = read_capacity(doc, path);
  return out;
}

ResultDocument read_result_document(const std::string& path) {
  return result_document_from_json(read_json_file(path), path);
}

}  // namespace crowdprof
