// Outputs through links and special files (issue 27, item 1): a link to a file
// is followed and the file replaced, the link kept; a dangling link creates its
// target; a pipe is written in place; "-" and /dev/stdout are standard output,
// written through the descriptor (never a file named "-", never a regular file
// over the link). Everything happens in a scratch folder: the machine's /dev
// is never touched (a scratch link to /proc/self/fd/1 stands in for /dev/stdout).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "base/errors.h"
#include "base/output_file.h"
#include "test_support.h"

using crowdprof::test::humanoid_glb;
using crowdprof::test::read_file;
using crowdprof::test::run_cli;
using crowdprof::test::shell_quoted;
namespace fs = std::filesystem;

TEST(OutputLinks, ALinkToAFileIsFollowedAndTheFileKeepsModeAndOwner) {
  auto dir = crowdprof::test::scratch_dir("links_file");
  fs::path target = dir / "target.csv", link = dir / "link.csv";
  std::ofstream(target) << "old";
  ASSERT_EQ(::chmod(target.c_str(), 0640), 0);
  bool root = ::geteuid() == 0;
  if (root) {
    ASSERT_EQ(::chown(target.c_str(), 4242, 4343), 0);
  }
  fs::create_symlink("target.csv", link);  // relative: to the link's folder
  crowdprof::write_file(link.string(), "CSV", "new");
  EXPECT_TRUE(fs::is_symlink(link)) << "the link was replaced by a file";
  EXPECT_EQ(read_file(target), "new");
  struct stat after {};
  ASSERT_EQ(::stat(target.c_str(), &after), 0);
  EXPECT_EQ(after.st_mode & 07777, 0640u);
  if (root) {
    EXPECT_EQ(after.st_uid, 4242u);
    EXPECT_EQ(after.st_gid, 4343u);
  }
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2u) << "a temporary file was left behind";
}

TEST(OutputLinks, ADanglingLinkCreatesItsTarget) {
  auto dir = crowdprof::test::scratch_dir("links_dangling");
  fs::create_directory(dir / "sub");
  fs::create_symlink("sub/made.json", dir / "link.json");
  crowdprof::require_writable((dir / "link.json").string(), "JSON");
  crowdprof::write_file((dir / "link.json").string(), "JSON", "{}");
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_EQ(read_file(dir / "sub" / "made.json"), "{}");
  // A link into a missing folder is refused before the run, naming both.
  fs::create_symlink("gone/x.json", dir / "nowhere.json");
  try {
    crowdprof::require_writable((dir / "nowhere.json").string(), "JSON");
    ADD_FAILURE() << "a link into a missing folder was accepted";
  } catch (const crowdprof::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("no folder"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is a link to"), std::string::npos) << e.what();
  }
}

TEST(OutputLinks, APipeIsWrittenInPlace) {
  auto dir = crowdprof::test::scratch_dir("links_pipe");
  fs::path fifo = dir / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string read;
  std::thread reader([&] { read = read_file(fifo); });
  crowdprof::write_file(fifo.string(), "CSV", "through the pipe");
  reader.join();
  EXPECT_EQ(read, "through the pipe");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(OutputLinks, StdoutThroughALinkFollowsWhatWasPrinted) {
  auto dir = crowdprof::test::scratch_dir("links_stdout");
  fs::create_symlink("/proc/self/fd/1", dir / "stdout");  // as /dev/stdout is
  auto r = run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 3 --warmup 0 --csv " +
                   shell_quoted(dir / "stdout"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir / "stdout")) << "the link was replaced by a file";
  // The CSV alone: the profile yields stdout to an output written there.
  EXPECT_EQ(r.out.rfind("frame,mode,", 0), 0u) << "stdout should hold the CSV alone:\n" << r.out;
  EXPECT_EQ(r.out.find("Frametime"), std::string::npos) << r.out;
}

TEST(OutputLinks, DashIsStandardOutput) {
  auto r = run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 3 --warmup 0 --csv -");
  bool made = fs::exists("-");
  if (made) fs::remove("-");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(made) << "--csv - wrote a file named '-'";
  EXPECT_EQ(r.out.rfind("frame,mode,", 0), 0u) << "stdout should hold the CSV alone:\n" << r.out;
  // Two outputs on stdout are two outputs on one path (a scratch link stands in
  // for /dev/stdout: a build that replaced links would replace only it).
  auto dir = crowdprof::test::scratch_dir("links_dash");
  fs::create_symlink("/proc/self/fd/1", dir / "stdout");
  r = run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 3 --csv - --json " +
              shell_quoted(dir / "stdout"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("both write"), std::string::npos) << r.err;
  // The report reads the screenshot back: stdout cannot be read back.
  r = run_cli("bench " + shell_quoted(humanoid_glb()) + " -n 2 --frames 3 --screenshot - --html " +
              shell_quoted(dir / "r.html"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("give --screenshot a file"), std::string::npos) << r.err;
}

TEST(OutputLinks, AnOutputLinkedToAnInputIsRefused) {
  auto dir = crowdprof::test::scratch_dir("links_overlap");
  fs::copy_file(crowdprof::test::source_dir() / "scenes" / "humanoid.glb", dir / "scene.glb");
  fs::create_symlink("scene.glb", dir / "link.csv");
  std::string before = read_file(dir / "scene.glb");
  auto r =
      run_cli("bench " + shell_quoted(dir / "scene.glb") + " -n 2 --frames 2 --csv " + shell_quoted(dir / "link.csv"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("is the character file"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "scene.glb"), before);
  // A dangling link leads to the file it would create: the same as another output.
  fs::create_symlink("t.json", dir / "a.csv");
  r = run_cli("bench " + shell_quoted(dir / "scene.glb") + " -n 2 --frames 2 --csv " + shell_quoted(dir / "a.csv") +
              " --json " + shell_quoted(dir / "t.json"));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("both write"), std::string::npos) << r.err;
}

TEST(OutputLinks, AFileInAFolderThatTakesNoNewFileIsWrittenInPlace) {
  auto dir = crowdprof::test::scratch_dir("links_in_place");
  fs::create_directory(dir / "ro");
  fs::path file = dir / "ro" / "f.csv";
  std::ofstream(file) << "old";
  fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  bool enforced = !std::ofstream(dir / "ro" / "probe");  // not for root
  fs::remove(dir / "ro" / "probe");
  if (enforced) {
    crowdprof::require_writable(file.string(), "CSV");
    crowdprof::write_file(file.string(), "CSV", "new");
    EXPECT_EQ(read_file(file), "new");
  }
  fs::permissions(dir / "ro", fs::perms::owner_all);
  if (!enforced) GTEST_SKIP() << "permission bits are not enforced for this user (root)";
}
