// `crowdprof diff A.json B.json`: two results (bench, check or compare JSON)
// side by side, for two builds of the same scene: exit 1 when B does other work,
// or its calibrated frame is slower than A's under check's rule (the only
// metric tested: lib/gate/diff.h says why). The logic is in lib/gate/diff.h.
#include <iostream>
#include <memory>

#include "base/errors.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "reports/html_report.h"
#include "base/output_file.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"
#include "gate/diff.h"

namespace {

using namespace crowdprof;

struct DiffCliOptions {
  std::string a, b;
  std::string tolerance = "7%";
  std::string floor = "2%";
  double alpha = 0.05;
  std::string json, html;
  bool quiet = false;
  DeclaredOutputs outputs;
};

int diff(const DiffCliOptions& o) {
  CheckOptions options;
  options.tolerance = parse_tolerance(o.tolerance);
  options.floor = parse_floor(o.floor);
  if (!(o.alpha > 0 && o.alpha < 1))
    throw UsageError("--alpha " + std::to_string(o.alpha) + ": expected between 0 and 1");
  options.alpha = o.alpha;
  o.outputs.files().require_usable({{"file A", o.a}, {"file B", o.b}});
  std::vector<Result> a = bench_results_in(read_json_file(o.a), o.a);
  std::vector<Result> b = bench_results_in(read_json_file(o.b), o.b);
  Diff result = diff_results(a, o.a, b, o.b, options);
  if (o.outputs.files().prints_on_stdout(o.quiet)) std::cout << format_diff(result, options);
  if (!o.json.empty())
    write_text(o.json, "JSON", [&](std::ostream& out) { out << diff_to_json(result, options).dump(2) << "\n"; });
  if (!o.html.empty()) {
    // A and B side by side; with one mode at one crowd size, its verdict per
    // metric too (a compare result's pairs are in the table and --json).
    HtmlReportInput input;
    add_result_file(input, o.a);
    add_result_file(input, o.b);
    input.command = "diff";
    if (result.pairs.size() == 1) input.check = CheckSection{result.pairs.front().check, options, o.a, "diff"};
    write_html_report(o.html, std::move(input));
  }
  return result.regressed() ? kExitRegression : kExitOk;
}

}  // namespace

void add_diff_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<DiffCliOptions>();
  auto* cmd = app.add_subcommand("diff",
                                 "Two results (bench, check or compare JSON) side by side, metric by metric: exit 1 "
                                 "when B does other work or its calibrated frame is slower. Only the calibrated "
                                 "frame is tested, where both have it; the other medians and changes are shown "
                                 "untested, since results run apart differ by the machine's drift (to test them, "
                                 "use compare or check --against). See docs/compare-and-check.md.");
  cmd->footer("Examples:\n  crowdprof diff before.json after.json");
  cmd->add_option("a", options->a, "Result A, the reference (bench --json, check --json or compare --json)")
      ->required();
  cmd->add_option("b", options->b, "Result B, judged against A")->required();
  cmd->add_option("--tolerance", options->tolerance,
                  "Slowdown of the calibrated frame's median allowed before a significant shift fails")
      ->capture_default_str();
  cmd->add_option("--floor", options->floor,
                  "Smallest slowdown of the calibrated frame's median that can fail: a time (0.05ms, 50us) or a share "
                  "of A's median")
      ->capture_default_str();
  cmd->add_option("--alpha", options->alpha, "Significance level of the Mann-Whitney U test, before Holm's correction")
      ->capture_default_str();
  options->outputs.declare(*cmd, OutputOption::Json, options->json, "Also write the comparison as JSON to this file");
  options->outputs.declare(*cmd, OutputOption::Html, options->html,
                           "Also write an HTML report of A and B side by side (docs/report.md)");
  cmd->add_flag("-q,--quiet", options->quiet, "Print nothing on stdout (the exit status and --json still tell)")
      ->group(kOutputsGroup);
  group_options(*cmd, kGateGroup, {"--tolerance", "--floor", "--alpha"});
  cmd->callback([&run, options] { run = [options] { return diff(*options); }; });
}
