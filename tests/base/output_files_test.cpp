// A command's output files, declared once: checked together before any work,
// and whether the command's own text may still go to stdout.
#include <gtest/gtest.h>

#include <string>

#include "base/errors.h"
#include "base/output_file.h"
#include "test_support.h"

namespace {

using namespace crowdprof;

std::string usable_error(const OutputFiles& files, const std::vector<NamedPath>& inputs) {
  try {
    files.require_usable(inputs);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(OutputFiles, OnlyTheFilesAskedForAreChecked) {
  auto dir = test::scratch_dir("output_files");
  OutputFiles files;
  files.add("--csv", "CSV", "");
  files.add("--json", "JSON", (dir / "run.json").string());
  EXPECT_EQ(usable_error(files, {{"character file", (dir / "a.glb").string()}}), "");
}

TEST(OutputFiles, AnInputOrASharedPathIsRefused) {
  auto dir = test::scratch_dir("output_files_shared");
  const std::string path = (dir / "x.json").string();
  OutputFiles files;
  files.add("--json", "JSON", path);
  EXPECT_NE(usable_error(files, {{"baseline", path}}), "");
  files.add("--html", "HTML", path);
  EXPECT_NE(usable_error(files, {}), "");
}

TEST(OutputFiles, AFolderThatIsMissingCannotTakeTheFile) {
  OutputFiles files;
  files.add("--svg", "SVG", "/no-such-folder-crowdprof/chart.svg");
  EXPECT_NE(usable_error(files, {}).find("SVG"), std::string::npos);
}

TEST(OutputFiles, StdoutIsFreeUnlessQuietOrAFileIsOnIt) {
  OutputFiles files;
  files.add("--json", "JSON", "run.json");
  EXPECT_TRUE(files.prints_on_stdout(false));
  EXPECT_FALSE(files.prints_on_stdout(true));
  files.add("--markdown", "Markdown", "-");
  EXPECT_FALSE(files.prints_on_stdout(false));
}

}  // namespace
