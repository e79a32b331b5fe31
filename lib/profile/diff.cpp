#include "profile/diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "asset/errors.h"
#include "profile/category_clock.h"
#include "profile/environment.h"
#include "profile/number_text.h"

namespace crowdprof {

namespace {

using nlohmann::json;

std::string p_value(double p) {
  char text[32];
  std::snprintf(text, sizeof text, p < 1e-4 ? "%.1e" : "%.4f", p);
  return text;
}

double median_of(const json& doc, const std::string& key) {
  return summarize(doc["samples"][key].get<std::vector<double>>()).median;
}

const char* verdict(const MetricCheck& m, const CheckOptions& options) {
  if (m.regressed) return "SLOWER";
  if (m.change < -options.tolerance && m.p_adjusted < options.alpha && m.test.z < 0) return "faster";
  return "same";
}

}  // namespace

std::vector<nlohmann::json> bench_results_in(const nlohmann::json& doc, const std::string& path) {
  bool is_compare = doc.is_object() && doc.contains("crowdprof") && doc["crowdprof"].is_object() &&
                    doc["crowdprof"].value("kind", json("bench")) == "compare";
  if (!is_compare) {
    validate_result(doc, path);
    return {doc};
  }
  if (!doc.contains("runs") || !doc["runs"].is_array() || doc["runs"].empty())
    throw InputError(path, "a compare result without \"runs\"");
  std::vector<json> out;
  for (size_t i = 0; i < doc["runs"].size(); ++i) {
    validate_result(doc["runs"][i], path + " (runs[" + std::to_string(i) + "])");
    out.push_back(doc["runs"][i]);
  }
  return out;
}

bool Diff::regressed() const {
  return std::any_of(pairs.begin(), pairs.end(), [](const DiffPair& p) { return p.check.regressed(); });
}

Diff diff_results(const std::vector<nlohmann::json>& a, const std::string& path_a,
                  const std::vector<nlohmann::json>& b, const std::string& path_b, const CheckOptions& options) {
  Diff diff;
  diff.a = path_a;
  diff.b = path_b;
  for (const json& ra : a) {
    auto match = std::find_if(b.begin(), b.end(), [&](const json& rb) {
      return rb["mode"] == ra["mode"] && rb["scene"]["characters"] == ra["scene"]["characters"];
    });
    if (match == b.end()) continue;
    const json& rb = *match;
    DiffPair pair;
    pair.mode = ra["mode"].get<std::string>();
    pair.characters = ra["scene"]["characters"].get<size_t>();
    CheckOptions mine = options;
    mine.metrics.clear();
    if (ra["samples"].contains("cpu_ms") && rb["samples"].contains("cpu_ms")) mine.metrics.push_back("cpu_ms");
    mine.metrics.push_back("frame_ms");
    for (size_t c = 0; c < kCategoryCount; ++c) {
      std::string key(category_name(static_cast<Category>(c)));
      if (std::max(median_of(ra, key), median_of(rb, key)) >= 0.005) mine.metrics.push_back(key);
    }
    pair.check = check_results(ra, rb, mine);
    for (const char* key : {"file", "character", "joints", "vertices", "action_choice", "camera", "resolution"}) {
      const json none = nullptr;
      const json& va = ra["scene"].contains(key) ? ra["scene"][key] : none;
      const json& vb = rb["scene"].contains(key) ? rb["scene"][key] : none;
      if (va != vb) pair.notes.push_back("scene " + std::string(key) + " " + va.dump() + " in A, " + vb.dump() + " in B");
    }
    for (const char* key : {"switches", "threads", "frames", "warmup", "fps"})
      if (ra[key] != rb[key]) pair.notes.push_back(std::string(key) + " " + ra[key].dump() + " in A, " + rb[key].dump() + " in B");
    diff.pairs.push_back(std::move(pair));
  }
  if (diff.pairs.empty())
    throw InputError(path_b, "no mode and crowd size in common with " + path_a + " (diff pairs results by mode and -n)");
  return diff;
}

std::string format_diff(const Diff& diff, const CheckOptions& options) {
  std::ostringstream out;
  out << "A: " << diff.a << "\nB: " << diff.b << "\n";
  for (const DiffPair& pair : diff.pairs) {
    const CheckResult& r = pair.check;
    double floor = r.metrics.empty() ? 0.0 : r.metrics.front().floor_ms;
    out << "\n" << pair.mode << ", " << pair.characters << " characters (tolerance " << fixed(options.tolerance * 100, 1)
        << "%, floor " << fixed(floor, 3) << " ms, p Holm-corrected over " << r.metrics.size() << " metrics)\n";
    char line[200];
    std::snprintf(line, sizeof line, "%-12s %12s %12s %9s %9s %9s  %s\n", "metric", "A median ms", "B median ms",
                  "change", "p", "p Holm", "verdict");
    out << line;
    for (const MetricCheck& m : r.metrics) {
      std::snprintf(line, sizeof line, "%-12s %12.3f %12.3f %9s %9s %9s  %s\n", m.metric.c_str(), m.baseline.median,
                    m.current.median, percent(m.change).c_str(), p_value(m.test.p).c_str(),
                    p_value(m.p_adjusted).c_str(), verdict(m, options));
      out << line;
    }
    if (r.counters.empty() && r.counters_missing.empty()) out << "counters: same\n";
    for (const CounterDifference& d : r.counters)
      out << "counter " << d.name << ": " << d.baseline << " -> " << d.current << " per frame: CHANGED\n";
    for (const std::string& name : r.counters_missing) out << "counter " << name << ": in A, missing in B: CHANGED\n";
    out << "digest: " << r.baseline_digest;
    if (r.digest_differs()) out << " -> " << r.current_digest << ": CHANGED\n";
    else out << ", same\n";
    for (const std::string& note : pair.notes) out << "note: " << note << "\n";
  }
  out << (diff.regressed() ? "REGRESSION: B is slower or does other work than A\n" : "ok: B is not slower than A and does the same work\n");
  return out.str();
}

nlohmann::json diff_to_json(const Diff& diff, const CheckOptions& options) {
  Environment env = current_environment();
  json j;
  j["crowdprof"] = {{"version", env.version}, {"commit", env.commit}, {"kind", "diff"}};
  j["a"] = diff.a;
  j["b"] = diff.b;
  j["tolerance"] = options.tolerance;
  j["alpha"] = options.alpha;
  j["pairs"] = json::array();
  for (const DiffPair& pair : diff.pairs) {
    const CheckResult& r = pair.check;
    json p = {{"mode", pair.mode}, {"characters", pair.characters}, {"regressed", r.regressed()}, {"notes", pair.notes}};
    p["metrics"] = json::array();
    for (const MetricCheck& m : r.metrics)
      p["metrics"].push_back({{"metric", m.metric},
                              {"a_median_ms", m.baseline.median},
                              {"b_median_ms", m.current.median},
                              {"change", std::isfinite(m.change) ? json(m.change) : json(nullptr)},
                              {"p", m.test.p},
                              {"p_holm", m.p_adjusted},
                              {"floor_ms", m.floor_ms},
                              {"verdict", verdict(m, options)}});
    p["counters"] = json::array();
    for (const CounterDifference& d : r.counters) p["counters"].push_back({{"name", d.name}, {"a", d.baseline}, {"b", d.current}});
    for (const std::string& name : r.counters_missing) p["counters"].push_back({{"name", name}, {"a", nullptr}, {"b", nullptr}});
    p["digest"] = {{"a", r.baseline_digest}, {"b", r.current_digest}, {"same", !r.digest_differs()}};
    j["pairs"].push_back(p);
  }
  j["regressed"] = diff.regressed();
  return j;
}

}  // namespace crowdprof
