// `crowdprof report RESULT.json [MORE.json ...] -o report.html`: the HTML
// report of results already written (bench, check, compare, capacity or advise --json). Every
// input is read and checked before anything is written, so a bad file leaves
// no report behind.
#include <iostream>

#include "base/errors.h"
#include "cli/bench_options.h"
#include "cli/commands.h"
#include "reports/html_report.h"
#include "base/output_file.h"
#include "frame/run_bench.h"
#include "result/result_codec.h"

namespace {

using namespace crowdprof;

struct ReportCliOptions {
  std::vector<std::string> files;
  std::string output, screenshot;
  DeclaredOutputs outputs;
};

int report(const ReportCliOptions& o) {
  std::vector<NamedPath> inputs = {{"--screenshot", o.screenshot}};
  for (const std::string& file : o.files) inputs.push_back({"result file", file});
  o.outputs.files().require_usable(inputs);  // distinct from the inputs by path, link or inode; writable
  HtmlReportInput input;
  for (const std::string& file : o.files) add_result_file(input, file);
  if (!o.screenshot.empty()) input.screenshot_png = read_png(o.screenshot);
  write_html_report(o.output, std::move(input));
  if (o.outputs.files().prints_on_stdout(false))  // where the page went, to open it
    std::cout << "wrote " << o.output << ": " << o.files.size() << (o.files.size() == 1 ? " result" : " results")
              << (o.screenshot.empty() ? "" : " and a screenshot") << "\n";
  return kExitOk;
}

}  // namespace

void add_report_command(CLI::App& app, std::function<int()>& run) {
  auto options = std::make_shared<ReportCliOptions>();
  auto* cmd = app.add_subcommand("report",
                                 "Write an HTML report (charts, tables, environment) of results of bench, "
                                 "check, compare, capacity or advise --json: one file that opens in any browser");
  cmd->footer("Examples:\n  crowdprof report result.json -o report.html");
  cmd->add_option("results", options->files,
                  "Result files (JSON) of bench, check, compare, capacity or advise --json; several: side by side")
      ->required();
  // What the page is made of and where it goes, one heading.
  options->outputs.declare(*cmd, OutputOption::HtmlPage, options->output, "The HTML file to write")
      ->required()
      ->group("Report");
  cmd->add_option("--screenshot", options->screenshot, "A PNG (bench --screenshot) to show in the report")
      ->group("Report");
  cmd->callback([&run, options] { run = [options] { return report(*options); }; });
}
