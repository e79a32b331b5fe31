// Never lose a user's file: an output that is an input, or two outputs on one
// path, is refused before any work with the input byte for byte unchanged;
// outputs are replaced atomically; a folder that cannot take a file is found
// before the run; and --version says what build this is.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/errors.h"
#include "base/output_file.h"
#include "test_support.h"

using crowdprof::test::read_file;
using crowdprof::test::run_cli;
namespace fs = std::filesystem;

namespace {

// A private copy of the default character, so a test that failed could only
// ever hurt the copy.
fs::path character_copy(const fs::path& dir) {
  fs::path copy = dir / "X.glb";
  fs::copy_file(crowdprof::test::source_dir() / "scenes" / "humanoid.glb", copy, fs::copy_options::overwrite_existing);
  return copy;
}

void expect_refused(const std::string& args, const fs::path& input, const std::string& words) {
  std::string before = read_file(input);
  auto r = run_cli(args);
  EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(words), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(read_file(input), before) << args << " changed " << input;
}

}  // namespace

TEST(SafeOutput, AnOutputThatIsTheInputIsRefusedAndTheInputUnchanged) {
  auto dir = crowdprof::test::scratch_dir("safe_same_input");
  fs::path x = character_copy(dir);
  std::string q = "'" + x.string() + "'";
  expect_refused("bench " + q + " -n 2 --frames 2 --json " + q, x, "--json " + x.string() + " is the character file");
  expect_refused("bench " + q + " -n 2 --frames 2 --csv " + q, x, "is the character file");
  expect_refused("render " + q + " -n 2 --backend osmesa -o " + q, x, "-o " + x.string() + " is the character file");
  expect_refused("check " + q + " -n 2 --frames 2 --baseline " + q + " --update-baseline", x,
                 "--baseline " + x.string() + " is the character file");
  expect_refused("compare " + q + " -n 2 --frames 2 --svg " + q, x, "is the character file");
  // Another spelling of the same path, a symbolic link and a hard link are the same file.
  std::string dotted = "'" + (dir / "." / "X.glb").string() + "'";
  expect_refused("bench " + q + " -n 2 --frames 2 --trace " + dotted, x, "is the character file");
  fs::create_symlink(x, dir / "link.glb");
  expect_refused("bench " + q + " -n 2 --frames 2 --json '" + (dir / "link.glb").string() + "'", x,
                 "is the character file");
  fs::create_hard_link(x, dir / "hard.glb");
  expect_refused("bench '" + (dir / "hard.glb").string() + "' -n 2 --frames 2 --json " + q, x, "is the character file");
  // FILE#skin=N is the file.
  expect_refused("bench '" + x.string() + "#skin=0' -n 2 --frames 2 --json " + q, x, "is the character file");
}

// A .gltf reads its buffers and textures beside it: they are inputs too.
TEST(SafeOutput, AnOutputOnAFileTheGltfReadsIsRefused) {
  auto dir = crowdprof::test::scratch_dir("safe_gltf_external");
  // URIs decoded as tiny_gltf decodes them: "p+q.bin" reads "p q.bin".
  std::ofstream(dir / "X.gltf") << R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "X.bin", "byteLength": 4}, {"uri": "p+q.bin", "byteLength": 4}],
    "images": [{"uri": "skin%20tex.png"}, {"uri": "data:image/png;base64,AAAA"}]})";
  std::ofstream(dir / "p q.bin") << "efgh";
  std::ofstream(dir / "X.bin") << "abcd";
  std::ofstream(dir / "skin tex.png") << "not really a png";
  std::ofstream(dir / "scene.json") << R"({"characters": [{"file": "X.gltf", "count": 2}]})";
  const std::string g = "'" + (dir / "X.gltf").string() + "'", s = "'" + (dir / "scene.json").string() + "'";
  const std::string bin = "'" + (dir / "X.bin").string() + "'", png = "'" + (dir / "skin tex.png").string() + "'";
  expect_refused("bench " + g + " -n 2 --frames 2 --csv " + bin, dir / "X.bin", "is the file read by");
  expect_refused("bench " + g + " -n 2 --frames 2 --screenshot " + png, dir / "skin tex.png", "is the file read by");
  expect_refused("check " + g + " -n 2 --frames 2 --baseline " + bin + " --update-baseline", dir / "X.bin",
                 "--baseline " + (dir / "X.bin").string() + " is the file read by");
  expect_refused("bench " + s + " --frames 2 --json " + bin, dir / "X.bin", "is the file read by");
  expect_refused("bench " + g + " -n 2 --frames 2 --csv '" + (dir / "p q.bin").string() + "'", dir / "p q.bin",
                 "is the file read by");
}

TEST(SafeOutput, AnOutputOnACharacterOfTheSceneIsRefused) {
  auto dir = crowdprof::test::scratch_dir("safe_scene_character");
  fs::path x = character_copy(dir);
  fs::path scene = dir / "scene.json";
  std::ofstream(scene) << R"({"characters": [{"file": "X.glb", "count": 2}]})";
  std::string s = "'" + scene.string() + "'";
  std::string q = "'" + x.string() + "'";
  expect_refused("bench " + s + " --frames 2 --json " + q, x, "is the character file of the scene");
  expect_refused("render " + s + " --backend osmesa -o " + q, x, "is the character file of the scene");
  expect_refused("compare " + s + " --frames 2 --svg " + q, x, "is the character file of the scene");
  expect_refused("check " + s + " --frames 2 --baseline " + q + " --update-baseline", x,
                 "is the character file of the scene");
}

// report's page is a declared output (issue 54 item 2): refused when it is one
// of the results or cannot be written, and on stdout ("-o -") alone.
TEST(SafeOutput, ReportsPageIsADeclaredOutput) {
  auto dir = crowdprof::test::scratch_dir("safe_report_page");
  fs::path x = character_copy(dir);
  std::string result = (dir / "r.json").string();
  ASSERT_EQ(run_cli("bench '" + x.string() + "' -n 2 --frames 3 --warmup 0 -q --json '" + result + "'").status, 0);
  expect_refused("report '" + result + "' -o '" + result + "'", result, "-o " + result + " is the result file");
  expect_refused("report '" + result + "' -o '" + (dir / "none" / "page.html").string() + "'", result,
                 "cannot write HTML file");
  auto r = run_cli("report '" + result + "' -o -");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("<!DOCTYPE html>", 0), 0u) << r.out.substr(0, 200);
  EXPECT_EQ(r.out.find("wrote -"), std::string::npos);
}

TEST(SafeOutput, TwoOutputsOnOnePathAreRefused) {
  auto dir = crowdprof::test::scratch_dir("safe_two_outputs");
  fs::path x = character_copy(dir);
  std::string f = (dir / "F").string();
  std::ofstream(f) << "keep me";
  expect_refused("bench '" + x.string() + "' -n 2 --frames 2 --csv '" + f + "' --json '" + f + "'", f,
                 "--csv and --json both write " + f);
  EXPECT_EQ(read_file(f), "keep me");
  std::string base = (dir / "base.json").string();
  ASSERT_EQ(run_cli("bench '" + x.string() + "' -n 2 --frames 8 --warmup 0 -q --json '" + base + "'").status, 0);
  expect_refused("check --baseline '" + base + "' --csv '" + f + "' --svg '" + f + "'", f, "both write");
  expect_refused("check --result '" + base + "' --baseline '" + (dir / "b2.json").string() + "' --json '" + base + "'",
                 base, "is the --result file");
}

TEST(SafeOutput, AFolderThatCannotTakeAFileIsRefusedBeforeTheRun) {
  auto dir = crowdprof::test::scratch_dir("safe_folder");
  fs::path x = character_copy(dir);
  // /proc takes no new file, not even root's (who ignores permission bits).
  auto r = run_cli("bench '" + x.string() + "' -n 2 --frames 2 --json /proc/crowdprof_result.json");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("cannot write JSON file '/proc/crowdprof_result.json': the folder /proc cannot take a new file"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(r.out.empty()) << "the run went ahead:\n" << r.out;
  // A read-only folder, where permission bits are enforced (not for root).
  fs::create_directory(dir / "ro");
  fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  std::string probe = (dir / "ro" / "probe").string();
  bool enforced = !std::ofstream(probe);
  fs::remove(probe);
  if (enforced) {
    r = run_cli("bench '" + x.string() + "' -n 2 --frames 2 --csv '" + (dir / "ro" / "f.csv").string() + "'");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  fs::permissions(dir / "ro", fs::perms::owner_all);
}

TEST(SafeOutput, AWriteThatFailsLeavesTheEarlierFileAsItWas) {
  auto dir = crowdprof::test::scratch_dir("safe_atomic");
  fs::path path = dir / "result.json";
  std::ofstream(path) << "the earlier result";
  // Files larger than 64 bytes cannot be written: the write fails half-way.
  struct rlimit old {};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  auto previous = signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 64;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  bool threw = false;
  try {
    crowdprof::write_file(path.string(), "JSON", std::string(100000, 'x'));
  } catch (const crowdprof::UsageError& e) {
    threw = std::string(e.what()).find("cannot write JSON file") != std::string::npos;
  }
  setrlimit(RLIMIT_FSIZE, &old);
  signal(SIGXFSZ, previous);
  EXPECT_TRUE(threw);
  EXPECT_EQ(read_file(path), "the earlier result");
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u) << "a temporary file was left behind";

  // A good write replaces the file by renaming a new one over it (another
  // inode), keeping its permissions.
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  struct stat before {
  }, after{};
  ASSERT_EQ(stat(path.c_str(), &before), 0);
  crowdprof::write_file(path.string(), "JSON", "new");
  ASSERT_EQ(stat(path.c_str(), &after), 0);
  EXPECT_EQ(read_file(path), "new");
  EXPECT_NE(before.st_ino, after.st_ino);
  EXPECT_EQ(after.st_mode & 07777, 0640u);
}

TEST(Version, OneLineWithVersionCommitBuildCompilerAndSimd) {
  auto r = run_cli("--version");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(r.out.rfind("crowdprof 0.", 0), 0u) << r.out;
  for (const char* words : {"(commit ", ", SIMD "})
    EXPECT_NE(r.out.find(words), std::string::npos) << words << " in " << r.out;
  EXPECT_NE(r.out.find(CROWDPROF_TEST_BUILD_TYPE), std::string::npos) << r.out;
}
