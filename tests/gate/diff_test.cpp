// `crowdprof diff`: two results side by side with check's rule, counters and
// digest compared, compare results paired by mode, and bad files refused.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "gate/diff.h"
#include "result/result_codec.h"
#include "test_support.h"

using namespace crowdprof;
using crowdprof::test::run_cli;
using nlohmann::json;

namespace {

// A result whose every timed sample is `factor` times A's.
json scaled(json doc, double factor) {
  for (auto& [key, values] : doc["samples"].items())
    for (auto& v : values) v = v.get<double>() * factor;
  return doc;
}

}  // namespace

TEST(Diff, SideBySideWithTheGateRule) {
  auto dir = test::scratch_dir("diff_cli");
  std::string a = (dir / "a.json").string();
  ASSERT_EQ(run_cli("bench '" + test::humanoid_glb() +
                    "' -n 6 --frames 20 --warmup 1 --mode culled --calibrate -q --json '" + a + "'")
                .status,
            0);
  // Against itself: every metric the same, counters and digest the same.
  auto r = run_cli("diff '" + a + "' '" + a + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  for (const char* words : {"metric", "A median", "B median", "p Holm", "\ncalibrated ", "\ncpu ", "\nframe ",
                            "counters: same", ", same\n", "ok: B is not slower"})
    EXPECT_NE(r.out.find(words), std::string::npos) << words << " in\n" << r.out;
  // Twice as slow everywhere but the probe: the calibrated frame is SLOWER,
  // exit 1; the timings measured apart are shown, not tested.
  json slower = scaled(test::read_json(a), 2.0);
  slower["samples"]["probe_ms"] = test::read_json(a)["samples"]["probe_ms"];
  std::string b = test::write_json(dir / "b.json", slower);
  std::string out = (dir / "diff.json").string();
  r = run_cli("diff '" + a + "' '" + b + "' --json '" + out + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("\ncalibrated "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("SLOWER"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("+100.0%         -         -  not tested"), std::string::npos) << r.out;
  json j = test::read_json(out);
  EXPECT_EQ(j["crowdprof"]["kind"], "diff");
  EXPECT_TRUE(j["regressed"].get<bool>());
  ASSERT_EQ(j["pairs"].size(), 1u);
  EXPECT_EQ(j["pairs"][0]["mode"], "culled");
  EXPECT_EQ(j["pairs"][0]["metrics"][0]["metric"], "calibrated");
  EXPECT_EQ(j["pairs"][0]["metrics"][0]["verdict"], "SLOWER");
  EXPECT_EQ(j["pairs"][0]["metrics"][1]["metric"], "cpu");
  EXPECT_NEAR(j["pairs"][0]["metrics"][1]["change"].get<double>(), 1.0, 1e-9);
  EXPECT_EQ(j["pairs"][0]["metrics"][1]["verdict"], "not tested");
  EXPECT_TRUE(j["pairs"][0]["metrics"][1]["p"].is_null());
  // B twice as fast: faster, exit 0.
  r = run_cli("diff '" + b + "' '" + a + "'");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("faster"), std::string::npos) << r.out;
  // Without the calibrated frame nothing is tested: no p-value, no verdict,
  // and the way to a tested change said; other work still fails.
  json plain_a = test::read_json(a), plain_b = slower;
  for (json* doc : {&plain_a, &plain_b}) {
    (*doc)["samples"].erase("calibrated");
    (*doc)["samples"].erase("probe_ms");
    doc->erase("calibration");
  }
  const std::string pa = test::write_json(dir / "plain_a.json", plain_a),
                    pb = test::write_json(dir / "plain_b.json", plain_b);
  r = run_cli("diff '" + pa + "' '" + pb + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("SLOWER"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("tolerance"), std::string::npos) << r.out;
  for (const char* words :
       {"not tested: A and B ran apart, not interleaved", "crowdprof compare", "crowdprof check --against BASE_BINARY",
        "ok: B does the same work as A (its timings are not tested)"})
    EXPECT_NE(r.out.find(words), std::string::npos) << words << " in\n" << r.out;
  // A floor above any change passes the slowdown.
  r = run_cli("diff '" + a + "' '" + b + "' --floor 10s -q");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_TRUE(r.out.empty());
  // Other work: a counter and the digest.
  json other = test::read_json(a);
  other["counters"]["poses_updated"] = 12345;
  other["digest"] = "0000000000000000";
  r = run_cli("diff '" + a + "' '" + test::write_json(dir / "other.json", other) + "'");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("counter poses_updated: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0000000000000000: CHANGED"), std::string::npos) << r.out;
  // --html: A and B side by side under the verdict; never over an input.
  std::string html = (dir / "diff.html").string();
  r = run_cli("diff '" + a + "' '" + b + "' -q --html '" + html + "'");
  EXPECT_EQ(r.status, 1) << r.err;
  std::ifstream in(html);
  std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("<section id=\"check\">"), std::string::npos);
  // The page says what made it: a diff, not a check.
  EXPECT_NE(page.find(", diff</title>"), std::string::npos) << page.substr(0, 600);
  EXPECT_EQ(page.find(", check</title>"), std::string::npos);
  EXPECT_NE(page.find("<h2>Diff against "), std::string::npos);
  EXPECT_NE(page.find("<th>A median</th><th>B median</th>"), std::string::npos);
  EXPECT_EQ(page.find("baseline"), std::string::npos) << "a diff has no baseline";
  EXPECT_NE(page.find("a.json"), std::string::npos);
  EXPECT_NE(page.find("b.json"), std::string::npos);
  EXPECT_EQ(run_cli("diff '" + a + "' '" + b + "' --html '" + b + "'").status, 2);
}

TEST(Diff, CompareResultsArePairedByMode) {
  auto dir = test::scratch_dir("diff_compare");
  std::string c = (dir / "c.json").string(), t = (dir / "t.json").string();
  ASSERT_EQ(run_cli("compare '" + test::humanoid_glb() +
                    "' -n 6 --frames 10 --warmup 1 --modes master,threaded -q --json '" + c + "'")
                .status,
            0);
  ASSERT_EQ(
      run_cli("bench '" + test::humanoid_glb() + "' -n 6 --frames 10 --warmup 1 --mode threaded -q --json '" + t + "'")
          .status,
      0);
  auto r = run_cli("diff '" + c + "' '" + c + "'");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("\nmaster, 6 characters"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nthreaded, 6 characters"), std::string::npos) << r.out;
  r = run_cli("diff '" + c + "' '" + t + "' --tolerance 900%");
  EXPECT_NE(r.out.find("\nthreaded, 6 characters"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("\nmaster"), std::string::npos) << r.out;
  // Two single results of the character: compared whatever their modes and
  // sizes, with what differs said, and other work is other work.
  std::string m = (dir / "m.json").string();
  ASSERT_EQ(
      run_cli("bench '" + test::humanoid_glb() + "' -n 7 --frames 10 --warmup 1 --mode master -q --json '" + m + "'")
          .status,
      0);
  r = run_cli("diff '" + t + "' '" + m + "'");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("\nthreaded (A) against master (B), 6 characters"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("note: mode \"threaded\" in A, \"master\" in B"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("note: characters 6 in A, 7 in B"), std::string::npos) << r.out;
  // A compare and a bench with nothing in common: refused.
  r = run_cli("diff '" + c + "' '" + m + "'");
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("no mode and crowd size in common"), std::string::npos) << r.err;
  // Another character: refused, as check refuses it.
  std::string fox = (dir / "fox.json").string();
  nlohmann::json other = nlohmann::json::parse(std::ifstream(t));
  other["scene"]["character"] = other["crowd"][0]["character"] = "Fox";
  other["crowd"][0]["asset_hash"] = "0123456789abcdef";  // another file's content
  std::ofstream(fox) << other.dump();
  r = run_cli("diff '" + t + "' '" + fox + "'");
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("of another character than"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(Diff, BadFilesAndOutputs) {
  auto dir = test::scratch_dir("diff_bad");
  std::string a = (dir / "a.json").string();
  ASSERT_EQ(
      run_cli("bench '" + test::humanoid_glb() + "' -n 4 --frames 8 --warmup 0 --mode culled -q --json '" + a + "'")
          .status,
      0);
  std::ofstream(dir / "cut.json") << test::read_json(a).dump().substr(0, 100);
  auto r = run_cli("diff '" + a + "' '" + (dir / "cut.json").string() + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_NE(r.err.find("cut.json: truncated JSON"), std::string::npos) << r.err;
  r = run_cli("diff '" + a + "' '" + (dir / "missing.json").string() + "'");
  EXPECT_EQ(r.status, 3) << r.err;
  std::string before = test::read_json(a).dump();
  r = run_cli("diff '" + a + "' '" + a + "' --json '" + a + "'");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is the file A"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_json(a).dump(), before);
  r = run_cli("diff '" + a + "' '" + a + "' --tolerance ten");
  EXPECT_EQ(r.status, 2) << r.err;
}

// A character is its file's content where both results recorded it: a renamed
// file is the same character, an edited one another whatever its name.
TEST(Diff, TheSameCharacterIsTheSameFileContent) {
  const auto dir = test::scratch_dir("diff_content");
  auto r = run_cli("bench '" + test::humanoid_glb() + "' -n 4 --frames 3 --warmup 0 -q --json '" +
                   (dir / "a.json").string() + "'");
  ASSERT_EQ(r.status, 0) << r.err;
  json a = test::read_json((dir / "a.json").string());
  ASSERT_TRUE(a["crowd"][0].contains("asset_hash")) << a["crowd"];
  auto diff_of = [&](const json& b_doc) {
    std::vector<Result> ra{result_from_json(a, "a.json")}, rb{result_from_json(b_doc, "b.json")};
    return diff_results(ra, "a.json", rb, "b.json", CheckOptions{});
  };
  json renamed = a;
  renamed["scene"]["character"] = renamed["crowd"][0]["character"] = "hero";
  EXPECT_NO_THROW(diff_of(renamed));
  json edited = a;
  edited["crowd"][0]["asset_hash"] = "0123456789abcdef";
  EXPECT_THROW(diff_of(edited), InputError);
  // Results without hashes (recorded before them) compare by name.
  json old_a = a, old_renamed = renamed;
  old_a["crowd"][0].erase("asset_hash");
  old_renamed["crowd"][0].erase("asset_hash");
  a = old_a;
  EXPECT_THROW(diff_of(old_renamed), InputError);
  EXPECT_NO_THROW(diff_of(old_a));
}

// A mesh-LOD result from before a copy drawn whole digested as without mesh LOD
// (no "digest_scheme") hashed every copy's level: its digest is not compared,
// and the line says to record it again. Without mesh LOD nothing changed.
TEST(Diff, AMeshLodDigestOfTheOldSchemeIsNotCompared) {
  auto dir = test::scratch_dir("diff_digest_scheme");
  const std::string now = (dir / "now.json").string(), plain = (dir / "plain.json").string();
  const std::string bench = "bench '" + test::humanoid_glb() + "' -n 4 --frames 2 --warmup 1 -q --backend none ";
  ASSERT_EQ(run_cli(bench + "--mesh-lod on --json '" + now + "'").status, 0);
  ASSERT_EQ(run_cli(bench + "--json '" + plain + "'").status, 0);
  for (const std::string& path : {now, plain}) {
    nlohmann::json old = test::read_json(path);
    EXPECT_EQ(old["digest_scheme"], kDigestScheme);
    old.erase("digest_scheme");
    old["digest"] = "0123456789abcdef";
    const std::string before = test::write_json(dir / "before.json", old);
    auto r = run_cli("diff '" + before + "' '" + path + "'");
    if (path == now) {
      EXPECT_EQ(r.status, 0) << r.out << r.err;
      EXPECT_NE(r.out.find("not compared: one was recorded before a copy drawn whole under mesh LOD"),
                std::string::npos)
          << r.out;
    } else {
      EXPECT_EQ(r.status, 1) << r.out << r.err;
      EXPECT_NE(r.out.find("CHANGED"), std::string::npos) << r.out;
    }
  }
}
