#include "gate/diff.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "base/errors.h"
#include "base/number_text.h"
#include "measuring/category_clock.h"
#include "measuring/environment.h"
#include "result/result_codec.h"
#include "result/run_match.h"

namespace crowdprof {

namespace {

using nlohmann::json;

// A value as the notes show it: strings quoted, numbers bare.
template <typename T>
std::string shown(const T& value) {
  return json(value).dump();
}

const char* verdict(const MetricCheck& m, const CheckOptions& options) {
  if (!m.tested) return "not tested";
  if (m.regressed) return "SLOWER";
  if (significantly_faster(m, options)) return "faster";
  return "same";
}

}  // namespace

bool Diff::tested() const {
  return std::any_of(pairs.begin(), pairs.end(), [](const DiffPair& p) {
    return std::any_of(p.check.metrics.begin(), p.check.metrics.end(), [](const MetricCheck& m) { return m.tested; });
  });
}

bool Diff::regressed() const {
  return std::any_of(pairs.begin(), pairs.end(), [](const DiffPair& p) { return p.check.regressed(); });
}

Diff diff_results(const std::vector<Result>& a, const std::string& path_a, const std::vector<Result>& b,
                  const std::string& path_b, const CheckOptions& options) {
  Diff diff;
  diff.a = path_a;
  diff.b = path_b;
  // Results of another character are refused, as check refuses them. A
  // character is its file's content where both sides recorded it (a renamed
  // file is the same character; an edited one is another, whatever its
  // name), else its name (results before asset hashes).
  auto join = [](const std::set<std::string>& items) {
    std::string joined;
    for (const std::string& item : items) joined += (joined.empty() ? "" : ", ") + item;
    return joined;
  };
  auto names = [&](const std::vector<Result>& results) {
    std::set<std::string> out;
    for (const Result& r : results) out.insert(r.run.character);
    return join(out);
  };
  // Every character's content hash, or empty when any is missing.
  auto contents = [&](const std::vector<Result>& results) {
    std::set<std::string> out;
    for (const Result& r : results) {
      if (r.run.crowd.empty()) return std::string();
      for (const CharacterRun& c : r.run.crowd) {
        if (c.content_hash.empty()) return std::string();
        out.insert(c.content_hash);
      }
    }
    return join(out);
  };
  const std::string content_a = contents(a), content_b = contents(b);
  if (!content_a.empty() && !content_b.empty()) {
    if (content_a != content_b)
      throw InputError(path_b, "of another character than " + path_a + ": asset " + content_a + " (" + shown(names(a)) +
                                   ") in A, " + content_b + " (" + shown(names(b)) +
                                   ") in B (diff compares results of one character, by its file's content)");
  } else if (names(a) != names(b)) {
    throw InputError(path_b, "of another character than " + path_a + ": " + shown(names(a)) + " in A, " +
                                 shown(names(b)) + " in B (diff compares results of one character)");
  }
  // Pairs by mode and crowd size; two single results of the character are a
  // pair whatever their modes and sizes, with what differs noted.
  std::vector<std::pair<const Result*, const Result*>> pairs;
  for (const Result& ra : a) {
    auto match = std::find_if(b.begin(), b.end(), [&](const Result& rb) {
      return rb.run.mode == ra.run.mode && rb.run.characters == ra.run.characters;
    });
    if (match != b.end()) pairs.emplace_back(&ra, &*match);
  }
  if (pairs.empty() && a.size() == 1 && b.size() == 1) pairs.emplace_back(&a.front(), &b.front());
  for (const auto& [pa, pb] : pairs) {
    const Result& ra = *pa;
    const Result& rb = *pb;
    DiffPair pair;
    pair.mode = ra.run.mode == rb.run.mode ? ra.run.mode : ra.run.mode + " (A) against " + rb.run.mode + " (B)";
    pair.characters = ra.run.characters;
    // A and B ran apart, not interleaved: the machine's speed moved between
    // them by more than any frame-to-frame test can tell from a change. Only
    // the calibrated frame (each frame over a probe timed beside it) is tested.
    CheckOptions tested = options;
    tested.metrics.clear();
    if (metric_samples(ra, "calibrated") && metric_samples(rb, "calibrated")) tested.metrics.push_back("calibrated");
    pair.check = check_results(ra, rb, tested);
    std::vector<std::string> shown_only;
    if (metric_samples(ra, "cpu_ms") && metric_samples(rb, "cpu_ms")) shown_only.push_back("cpu_ms");
    shown_only.push_back("frame_ms");
    for (size_t c = 0; c < kCategoryCount; ++c) {
      const std::string key = series_name(static_cast<Category>(c));
      if (std::max(metric_median(ra, key), metric_median(rb, key)) >= 0.005) shown_only.push_back(key);
    }
    for (const std::string& key : shown_only) {
      MetricCheck m =
          check_metric(metric_display_name(key), *metric_samples(ra, key), *metric_samples(rb, key), options);
      m.tested = false;  // its medians and change only: no verdict
      m.regressed = m.significant = false;
      pair.check.metrics.push_back(std::move(m));
    }
    auto note = [&](const std::string& what, const std::string& va, const std::string& vb) {
      if (va != vb) pair.notes.push_back(what + " " + va + " in A, " + vb + " in B");
    };
    // What makes two runs the same (result/run_match.h), then the threads,
    // which change the timings and not the work.
    for (const RunDifference& d : run_differences(ra, rb)) note(d.field, d.a, d.b);
    note("threads", shown(ra.run.threads), shown(rb.run.threads));
    diff.pairs.push_back(std::move(pair));
  }
  if (diff.pairs.empty())
    throw InputError(path_b,
                     "no mode and crowd size in common with " + path_a + " (diff pairs results by mode and -n)");
  return diff;
}

std::string format_diff(const Diff& diff, const CheckOptions& options) {
  std::ostringstream out;
  out << "A: " << diff.a << "\nB: " << diff.b << "\n";
  for (const DiffPair& pair : diff.pairs) {
    const CheckResult& r = pair.check;
    const auto tested =
        std::count_if(r.metrics.begin(), r.metrics.end(), [](const MetricCheck& m) { return m.tested; });
    out << "\n" << pair.mode << ", " << pair.characters << " characters";
    if (tested > 0) {
      const MetricCheck& first =
          *std::find_if(r.metrics.begin(), r.metrics.end(), [](const MetricCheck& m) { return m.tested; });
      out << " (tolerance " << fixed(options.tolerance * 100, 1) << "%, floor "
          << metric_value_text(first, first.floor_ms) << " " << first.value_unit << ", p Holm-corrected over " << tested
          << " metric" << (tested > 1 ? "s" : "") << ")";
    }
    out << "\n";
    char line[200];
    std::snprintf(line, sizeof line, "%-12s %12s %12s %9s %9s %9s  %s\n", "metric", "A median", "B median", "change",
                  "p", "p Holm", "verdict");
    out << line;
    for (const MetricCheck& m : r.metrics) {
      std::snprintf(line, sizeof line, "%-12s %12s %12s %9s %9s %9s  %s\n", m.metric.c_str(),
                    (metric_value_text(m, m.baseline.median) + (m.value_unit == "ms" ? " ms" : "")).c_str(),
                    (metric_value_text(m, m.current.median) + (m.value_unit == "ms" ? " ms" : "")).c_str(),
                    percent(m.change).c_str(), m.tested ? p_value_text(m.test.p).c_str() : "-",
                    m.tested ? p_value_text(m.p_adjusted).c_str() : "-", verdict(m, options));
      out << line;
    }
    if (std::any_of(r.metrics.begin(), r.metrics.end(), [](const MetricCheck& m) { return !m.tested; }))
      out << "not tested: A and B ran apart, not interleaved: their frames sample two moments of the machine, and the\n"
             "  change holds the machine's drift as well as yours. To test a change, run both in one process\n"
             "  (crowdprof compare) or build against build (crowdprof check --against BASE_BINARY).\n"
          << (tested > 0
                  ? "tested: the calibrated frame, each frame over a probe timed beside it, which the machine's\n"
                    "  drift moves less\n"
                  : "");
    if (r.counters.empty() && r.counters_missing.empty()) out << "counters: same\n";
    for (const CounterDifference& d : r.counters)
      out << "counter " << d.name << ": " << d.baseline << " -> " << d.current << " per frame: CHANGED\n";
    for (const std::string& name : r.counters_missing) out << "counter " << name << ": in A, missing in B: CHANGED\n";
    out << "digest: " << r.baseline_digest;
    if (r.baseline_digest == r.current_digest)
      out << ", same\n";
    else
      out << " -> " << r.current_digest << ": " << r.digest_note() << "\n";
    for (const std::string& note : pair.notes) out << "note: " << note << "\n";
  }
  out << (diff.regressed() ? "REGRESSION: B is slower or does other work than A\n"
          : diff.tested()  ? "ok: B is not slower than A and does the same work\n"
                           : "ok: B does the same work as A (its timings are not tested)\n");
  return out.str();
}

DiffRecord diff_record(const Diff& diff, const CheckOptions& options) {
  Environment env = current_environment();
  DiffRecord d;
  d.version = env.version;
  d.commit = env.commit;
  d.a = diff.a;
  d.b = diff.b;
  d.tolerance = options.tolerance;
  d.alpha = options.alpha;
  for (const DiffPair& pair : diff.pairs) {
    const CheckResult& r = pair.check;
    DiffRecord::Pair p{pair.mode,
                       pair.characters,
                       r.regressed(),
                       pair.notes,
                       {},
                       {},
                       r.baseline_digest,
                       r.current_digest,
                       r.digest_not_comparable() ? r.digest_note() : std::string()};
    for (const MetricCheck& m : r.metrics) {
      DiffRecord::Metric metric;
      metric.metric = m.metric;
      metric.unit = m.value_unit;
      metric.verdict = verdict(m, options);
      metric.a_median = m.baseline.median;
      metric.b_median = m.current.median;
      metric.floor_ms = m.floor_ms;
      if (std::isfinite(m.change)) metric.change = m.change;
      if (m.tested) {
        metric.p = m.test.p;
        metric.p_holm = m.p_adjusted;
      }
      metric.tested = m.tested;
      p.metrics.push_back(std::move(metric));
    }
    for (const CounterDifference& c : r.counters) p.counters.push_back({c.name, c.baseline, c.current});
    for (const std::string& name : r.counters_missing) p.counters.push_back({name, std::nullopt, std::nullopt});
    d.pairs.push_back(std::move(p));
  }
  d.regressed = diff.regressed();
  return d;
}

nlohmann::json diff_to_json(const Diff& diff, const CheckOptions& options) {
  return diff_record_to_json(diff_record(diff, options));
}

}  // namespace crowdprof
