// check's runner without the command line: a CheckRun is plain values, and
// what cannot be run is refused before any process starts.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "base/errors.h"
#include "frame/interrupt.h"
#include "gate/check_run.h"
#include "reports/check_report.h"

namespace {

using namespace crowdprof;

std::string usage_error_of(const CheckRun& request) {
  try {
    run_check(request);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(CheckRun, NeedsABaselineOrABaseBuild) {
  EXPECT_EQ(usage_error_of(CheckRun{}),
            "check needs --baseline FILE (a stored result) or --against BINARY (an A/B of two builds)");
}

TEST(CheckRun, ACountedMetricWritesNoTimedFiles) {
  CheckRun request;
  request.plan.metrics = {"instructions"};
  request.baseline = "base.json";
  request.given = {"--csv"};
  EXPECT_EQ(usage_error_of(request),
            "--csv is not written by --metric instructions (its runs are counted, not "
            "timed); --json, --junit and --markdown are");
}

TEST(CheckRun, AnAbRefusesWhatOnlyAStoredBaselineHas) {
  CheckRun request;
  request.against = "base/crowdprof";
  request.given = {"--runs"};
  EXPECT_EQ(usage_error_of(request), "--runs is not for an A/B: --against runs both builds and compares them");
  request.given.clear();
  request.plan.metrics = {"instructions"};
  EXPECT_EQ(usage_error_of(request),
            "--metric instructions is for a stored baseline: an A/B times both builds side by side");
  request.plan.metrics = {"frame"};
  EXPECT_EQ(usage_error_of(request), "check --against needs a scene FILE to run on both builds");
}

TEST(CheckRun, AMissingBaselineIsBadInput) {
  CheckRun request;
  request.baseline = "no-such-baseline.json";
  request.result = "no-such-result.json";
  request.plan.has_result = true;
  try {
    run_check(request);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file (record a baseline first with --update-baseline)"),
              std::string::npos)
        << e.what();
  }
}

TEST(CheckReport, AnInterruptedCheckWritesAndPrintsNothing) {
  std::ostringstream out;
  EXPECT_EQ(report_check(CheckRun{}, CheckOutcome{}, out), kExitInterrupted);
  EXPECT_EQ(out.str(), "");
}

}  // namespace
