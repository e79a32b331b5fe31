// Result files come from strangers (a CI artifact, a colleague's run), so every
// reader of one must finish or refuse it with one InputError, whatever was
// removed or retyped. Real results of every kind (bench, compare, check,
// capacity, diff; tiny runs of the CLI) are damaged one field at a time, each
// key removed and each value replaced by one of every other JSON type, and given
// in process to what `report`, `diff`, `check --result` and `check --baseline`
// read them with. Reaching nlohmann's JSON_ASSERT (base/json_assert.h) is a
// finding too: it means a read was not guarded, and only the net caught it. A
// sample goes through the CLI; hostile names must come out of the HTML report
// escaped; oversized claims must be refused before anything is allocated.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "base/json_assert.h"
#include "gltf_fixture.h"
#include "gate/diff.h"
#include "reports/html_report.h"
#include "gate/regression.h"
#include "result/result_codec.h"
#include "result/run_match.h"
#include "test_support.h"

namespace crowdprof::test {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Runs the CLI, failing the test unless it exits 0.
void cli(const std::string& args) {
  CliResult r = run_cli(args);
  ASSERT_EQ(r.status, 0) << "crowdprof " << args << "\n" << r.err;
}

// Real results of each kind from tiny runs of the tests' skinned character,
// made once per test process into `folder` (a kind needs only its own runs).
json make_result(const std::string& kind, const fs::path& folder) {
  const std::string character = (folder / "character.glb").string();
  if (!fs::exists(character)) SkinnedFixture().write_glb(character);
  const std::string run = " -q --backend none --frames 3 --warmup 1 '" + character + "'";
  const std::string out = (folder / (kind + ".json")).string();
  if (kind == "bench") {
    cli("bench" + run + " -n 2 --json '" + out + "'");
  } else if (kind == "compare") {
    cli("compare" + run + " --modes master,threaded --sweep 1,2 --json '" + out + "'");
  } else if (kind == "capacity") {
    cli("capacity" + run + " --budget 1000 --start 1 --max-characters 2 --json '" + out + "'");
  } else if (kind == "check") {
    // What check --json writes: a result pooled over its runs.
    cli("check" + run + " -n 2 --runs 2 --update-baseline --baseline '" + (folder / "baseline.json").string() +
        "' --json '" + out + "'");
  } else if (kind == "diff") {
    std::string bench = (folder / "bench.json").string();
    if (!fs::exists(bench)) make_result("bench", folder);
    cli("diff -q '" + bench + "' '" + bench + "' --json '" + out + "'");
  }
  return read_json(out);
}

const json& result(const std::string& kind) {
  static std::map<std::string, json> made;
  static const fs::path folder = scratch_dir("untrusted_results");
  auto found = made.find(kind);
  if (found == made.end()) found = made.emplace(kind, make_result(kind, folder)).first;
  return found->second;
}

// Values of other types to put in place of `value`: null, a boolean, a string,
// a number (a fraction for a whole number, a negative whole number for any
// other) and a container (an object for an array, an array for anything else).
// A reader's checks tell these apart; more of each type would only cost time.
std::vector<json> stand_ins(const json& value) {
  std::vector<json> out;
  for (json other : {json(nullptr), json(true), json("text")})
    if (other.type() != value.type()) out.push_back(other);
  out.push_back(value.is_number_integer() ? json(2.5) : json(-1));
  out.push_back(value.is_array() ? json::object() : json::array());
  return out;
}

struct Damage {
  std::string what;  // "removed /scene/file", "/frames as \"text\""
  json doc;
};

// Every damaged copy of `doc`: each key removed, each value retyped. Of an
// array only the first element is damaged (the rest are alike), so a result
// of many frames or runs costs no more than one of a few.
void damage(const json& doc, const json::json_pointer& at, std::vector<Damage>& out) {
  const json& node = doc[at];
  if (!at.empty()) {
    if (doc[at.parent_pointer()].is_object()) {
      json removed = doc;
      removed[at.parent_pointer()].erase(at.back());
      out.push_back({"removed " + at.to_string(), std::move(removed)});
    }
    for (const json& stand_in : stand_ins(node)) {
      json retyped = doc;
      retyped[at] = stand_in;
      out.push_back({at.to_string() + " as " + stand_in.dump(), std::move(retyped)});
    }
  }
  if (node.is_object())
    for (const auto& [key, value] : node.items()) damage(doc, at / key, out);
  else if (node.is_array() && !node.empty())
    damage(doc, at / 0, out);
}

std::vector<Damage> damaged(const json& doc) {
  std::vector<Damage> out;
  damage(doc, json::json_pointer(), out);
  return out;
}

// What each command does with a result file after reading it as JSON.
using Reader = std::function<void(const json& doc, const json& intact, const std::string& path)>;

void report_reader(const json& doc, const json&, const std::string& path) {
  HtmlReportInput input;
  input.sources = {path};
  add_document(input, result_document_from_json(doc, path), path);
  (void)html_report(input);
}

void diff_reader(const json& doc, const json& intact, const std::string& path) {
  CheckOptions options;
  std::vector<Result> runs = bench_results_in(doc, path);
  // Against itself, and against the intact result both ways (A and B differ).
  std::vector<Result> other = bench_results_in(intact, "intact.json");
  for (const auto& [a, b] : {std::pair{&runs, &runs}, {&runs, &other}, {&other, &runs}}) {
    try {
      Diff diff = diff_results(*a, path, *b, path, options);
      (void)format_diff(diff, options);
      (void)diff_to_json(diff, options).dump();
    } catch (const InputError& e) {
      // Nothing in common (a mode or -n damaged) is a refusal like any other,
      // unless the net caught it.
      if (dynamic_cast<const JsonAssertion*>(&e)) throw;
    }
  }
}

// check --result FILE (current) and check --baseline FILE: read_result, then
// what cmd_check does with the two documents.
void check_reader(const json& doc, const json& intact, const std::string& path, bool doc_is_baseline) {
  Result read = result_from_json(doc, path);
  Result whole = result_from_json(intact, "intact.json");
  const Result& baseline = doc_is_baseline ? read : whole;
  const Result& current = doc_is_baseline ? whole : read;
  try {
    require_same_run(baseline, current, path);
  } catch (const InputError& e) {
    if (dynamic_cast<const JsonAssertion*>(&e)) throw;
  }
  (void)comparison_notes(baseline, current);
  CheckOptions options;
  options.metrics = all_metrics();
  if (metric_samples(baseline, "cpu_ms") && metric_samples(current, "cpu_ms")) options.metrics.push_back("cpu_ms");
  CheckResult checked = check_results(baseline, current, options);
  (void)format_check(checked, options);
}

void check_result_reader(const json& doc, const json& intact, const std::string& path) {
  check_reader(doc, intact, path, false);
}
void check_baseline_reader(const json& doc, const json& intact, const std::string& path) {
  check_reader(doc, intact, path, true);
}

const std::pair<const char*, Reader> kReaders[] = {{"report", &report_reader},
                                                   {"diff", &diff_reader},
                                                   {"check --result", &check_result_reader},
                                                   {"check --baseline", &check_baseline_reader}};

// Reads `doc` with every reader; returns what went wrong, "" when each read it
// or refused it with one line.
std::string read_with_every_reader(const json& doc, const json& intact, const std::string& path) {
  std::string wrong;
  for (const auto& [name, reader] : kReaders) {
    try {
      reader(doc, intact, path);
    } catch (const JsonAssertion& e) {
      wrong += std::string(name) + ": an unguarded read reached nlohmann's JSON_ASSERT: " + e.what() + "; ";
    } catch (const InputError& e) {
      std::string what = e.what();
      if (what.find('\n') != std::string::npos)
        wrong += std::string(name) + ": a message of several lines: " + what + "; ";
    } catch (const std::exception& e) {
      wrong += std::string(name) + ": not an InputError (exit 4, not 3): " + e.what() + "; ";
    }
  }
  return wrong;
}

void every_reader_survives_every_damage(const std::string& kind) {
  const json& intact = result(kind);
  ASSERT_FALSE(intact.is_null());
  // The intact result itself is read by the readers of its kind.
  EXPECT_EQ(read_with_every_reader(intact, intact, kind + ".json"), "");
  std::vector<Damage> all = damaged(intact);
  size_t failures = 0;
  for (const Damage& d : all) {
    std::string wrong = read_with_every_reader(d.doc, intact, kind + ".json");
    if (!wrong.empty() && ++failures <= 20) ADD_FAILURE() << kind << " result, " << d.what << ": " << wrong;
  }
  EXPECT_EQ(failures, 0u) << "of " << all.size() << " damaged " << kind << " results";
  EXPECT_GT(all.size(), 100u) << "a real " << kind << " result has more fields than that";
}

TEST(UntrustedResults, BenchResultsDamagedAnywhere) {
  every_reader_survives_every_damage("bench");
}
TEST(UntrustedResults, CompareResultsDamagedAnywhere) {
  every_reader_survives_every_damage("compare");
}
TEST(UntrustedResults, CheckResultsDamagedAnywhere) {
  every_reader_survives_every_damage("check");
}
TEST(UntrustedResults, CapacityResultsDamagedAnywhere) {
  every_reader_survives_every_damage("capacity");
}
TEST(UntrustedResults, DiffResultsDamagedAnywhere) {
  every_reader_survives_every_damage("diff");
}

// nlohmann's JSON_ASSERT is crowdprof's (force-included by lib/CMakeLists.txt):
// a read it forbids throws, in a Release build too, instead of reading past the end.
TEST(UntrustedResults, NlohmannsAssertionThrowsAnInputError) {
  const json empty = json::object();
  EXPECT_THROW((void)empty["missing"], JsonAssertion);
  const json none = json::array();
  EXPECT_THROW((void)none.front(), JsonAssertion);
  try {
    (void)empty["missing"];
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nlohmann"), std::string::npos) << e.what();
  }
}

// A sample through the CLI: exit 0 or 3 and at most one line on stderr.
TEST(UntrustedResults, TheCliReadsDamagedResultsWithExit0Or3) {
  fs::path dir = scratch_dir("untrusted_results_cli");
  auto write = [&](const std::string& name, const json& doc) {
    std::string path = (dir / name).string();
    write_json(path, doc);
    return "'" + path + "'";
  };
  json no_reason = result("compare");  // the fuzz finding: one run's gpu_time without its reason
  no_reason["runs"][1]["gpu_time"].erase("reason");
  json available_as_text = result("bench");
  available_as_text["gpu_time"]["available"] = "yes";
  available_as_text["gpu_time"]["median_ms"] = "1";
  json no_environment = result("bench");
  no_environment.erase("environment");
  json no_frame = result("check");
  no_frame.erase("frame");
  json runs_as_text = result("compare");
  runs_as_text["runs"] = "text";
  const std::string bench = write("bench.json", result("bench"));
  const std::string html = "'" + (dir / "out.html").string() + "'";
  struct Case {
    std::string args;
    int status;
  };
  const std::string bench_options = " -q --backend none --frames 3 --warmup 1 --runs 1";
  std::vector<Case> cases = {
      {"report " + write("no_reason.json", no_reason) + " -o " + html, 0},
      {"report " + write("available_as_text.json", available_as_text) + " -o " + html, 0},
      {"diff -q " + bench + " " + write("available_as_text_b.json", available_as_text) + " --html " + html, 0},
      {"check --result " + write("no_environment.json", no_environment) + " --baseline " + bench, 0},
      // The baseline's options are adopted for the rerun: its missing environment
      // must not be read.
      {"check" + bench_options + " --baseline " + write("baseline_no_environment.json", no_environment), -1},
      {"check --result " + write("no_frame.json", no_frame) + " --baseline '" + (dir / "new_baseline.json").string() +
           "' --update-baseline",
       0},
      {"report " + write("runs_as_text.json", runs_as_text) + " -o " + html, 3},
  };
  for (const Case& c : cases) {
    CliResult r = run_cli(c.args);
    if (c.status >= 0) {
      EXPECT_EQ(r.status, c.status) << c.args << "\n" << r.err;
    }
    EXPECT_TRUE(r.status == 0 || r.status == 1 || r.status == 3) << c.args << ": exit " << r.status << "\n" << r.err;
    if (r.status == 3) {  // a refusal is one line (a run may print notes besides)
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << "\n" << r.err;
    }
    EXPECT_EQ(r.err.find("nlohmann"), std::string::npos) << "an unguarded read: " << c.args << "\n" << r.err;
  }
}

// Names from a stranger's result go into the HTML report escaped: no markup of
// theirs, no attribute broken out of, however long.
TEST(UntrustedResults, HostileNamesAreEscapedInTheHtmlReport) {
  json doc = result("compare");
  const std::string script = "<script>alert('x')</script>";
  const std::string quote = "\" onload=\"alert(1)";
  const std::string huge(1 << 20, 'w');
  doc["runs"][0]["mode"] = script;
  doc["runs"][1]["mode"] = quote;
  doc["sweep"][0]["mode"] = script + quote;
  for (json& run : doc["runs"]) {
    run["scene"]["character"] = script;
    run["scene"]["file"] = quote + ".glb";
    run["digest"] = "'" + script;
    run["environment"]["cpu"] = huge;
    run["environment"][script] = quote;
    run["counters"][quote] = 1;
    run["crowdprof"]["version"] = script;
    run["gpu_time"] = {{"available", false}, {"reason", script + huge}};
  }
  // A switch no crowdprof has is refused, by name, before anything shows it.
  json unknown_switch = doc;
  unknown_switch["runs"][0]["switches"][script] = quote;
  HtmlReportInput refused;
  try {
    add_document(refused, result_document_from_json(unknown_switch, "hostile.json"), "hostile.json");
    ADD_FAILURE() << "a switch no crowdprof has was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no switch '" + script + "'"), std::string::npos) << e.what();
  }
  HtmlReportInput input;
  input.sources = {quote + script + ".json"};
  add_document(input, result_document_from_json(doc, "hostile.json"), "hostile.json");
  std::string html = html_report(input);
  // The page's own two scripts (its error hook and self-check), none of theirs.
  size_t scripts = 0;
  for (size_t at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1)) ++scripts;
  EXPECT_EQ(scripts, 2u);
  EXPECT_EQ(html.find("<script>alert"), std::string::npos);
  EXPECT_EQ(html.find(quote), std::string::npos);
  EXPECT_EQ(html.find("onload=\""), std::string::npos);
  EXPECT_NE(html.find("&lt;script&gt;"), std::string::npos);
  EXPECT_NE(html.find(huge), std::string::npos) << "a long name is kept, escaped, not cut into markup";
}

// Sizes a file claims are checked against what it holds before anything is
// allocated for them.
TEST(UntrustedResults, OversizedClaimsAreRefused) {
  json frames = result("bench");
  frames["frames"] = 1'000'000'000;
  json runs = result("check");
  runs["runs"]["count"] = 1'000'000'000;
  json sweep = result("compare");
  sweep["sweep"][0]["characters"] = uint64_t{1} << 63;
  for (const auto& [what, doc] : {std::pair<const char*, json>{"frames", frames}, {"runs.count", runs}}) {
    EXPECT_THROW(result_from_json(doc, "big.json"), InputError) << what;
    EXPECT_EQ(read_with_every_reader(doc, result("bench"), "big.json"), "") << what;
  }
  EXPECT_EQ(read_with_every_reader(sweep, result("compare"), "big.json"), "");

  // A character whose accessors claim a billion elements in a few bytes.
  SkinnedFixture fixture;
  for (nlohmann::json& accessor : fixture.json["accessors"]) accessor["count"] = 1'000'000'000;
  fs::path dir = scratch_dir("untrusted_results_big");
  fixture.write_glb(dir / "big.glb");
  std::ifstream in(dir / "big.glb", std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_THROW(load_gltf_from_memory(bytes, (dir / "big.glb").string()), InputError);
  EXPECT_THROW(load_gltf((dir / "big.glb").string()), InputError);
}

}  // namespace
}  // namespace crowdprof::test
