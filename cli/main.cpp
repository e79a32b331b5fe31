// crowdprof: profile skinned-crowd scenes. This file only dispatches to the
// subcommands (cli/cmd_*.cpp) and turns errors into exit statuses:
// 2 for a bad command line, 3 for a bad input file, 4 when the run fails.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "base/errors.h"
#include "cli/usage_errors.h"
#include "cli/commands.h"
#include "cli/help_format.h"
#include "measuring/environment.h"
#include "skinning/output_stores.h"
#include "skinning/simd_target.h"

namespace {

// What was printed must have reached stdout: a full disk (or /dev/full) fails
// the command instead of leaving a cut output behind an exit status of 0.
int after_flushing_stdout(int status) {
  errno = 0;
  std::cout.flush();
  bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (!failed) return status;
  int error = errno;
  std::cerr << "crowdprof: cannot write to stdout" << (error ? std::string(": ") + std::strerror(error) : "") << "\n";
  return crowdprof::kExitRuntime;
}

int run_command(int argc, char** argv) {
  CLI::App app{"crowdprof: profile skinned-crowd scenes (after Stokes 2014, skeletal animation in the BGE)"};
  app.name("crowdprof");
  // Global options are taken anywhere, also after the command (a command
  // passes the options it does not know up to the app).
  app.fallthrough();
  // The SIMD target skinning runs on: the CPU's best, else CROWDPROF_SIMD, else
  // --simd (applied as soon as it is parsed, so that --version shows it).
  std::string simd_error;
  // An error from the environment names it: the user may not know it is set.
  auto from_environment = [](const char* variable, const std::string& error) {
    return error.empty() ? error : "the environment's " + std::string(variable) + ": " + error;
  };
  if (const char* from_env = std::getenv(crowdprof::kSimdEnvironmentVariable))
    simd_error = from_environment(crowdprof::kSimdEnvironmentVariable, crowdprof::force_simd_target(from_env));
  bool version = false;
  app.add_flag("-v,--version", version, "Print the version, commit, build type, compiler and SIMD target on one line");
  std::string compiled;  // the targets of this build, which Highway's version decides
  for (const std::string& name : crowdprof::compiled_simd_targets()) compiled += (compiled.empty() ? "" : ", ") + name;
  app.add_option_function<std::string>(
         "--simd", [&](const std::string& name) { simd_error = crowdprof::force_simd_target(name); },
         "Run skinning on this SIMD target instead of the CPU's best (this build: " + compiled +
             "; AVX3 is AVX-512; also the environment variable CROWDPROF_SIMD)")
      ->trigger_on_parse();
  // How skinned vertices are stored (output_stores.h): CROWDPROF_STORES, else --stores.
  std::string stores_error;
  if (const char* from_env = std::getenv(crowdprof::kStoresEnvironmentVariable))
    stores_error = from_environment(crowdprof::kStoresEnvironmentVariable, crowdprof::force_output_stores(from_env));
  app.add_option_function<std::string>(
         "--stores", [&](const std::string& name) { stores_error = crowdprof::force_output_stores(name); },
         "How CPU skinning writes float vertices: auto (streaming stores when a frame's output is larger than "
         "64 MiB), regular or streaming (also the environment variable CROWDPROF_STORES)")
      ->trigger_on_parse();
  app.require_subcommand(0, 1);  // none only with --version or --help
  app.footer(
      "Each command lists its options: crowdprof bench --help\n\nExamples:\n  crowdprof bench scenes/thesis.json");
  std::function<int()> run;
  add_info_command(app, run);
  add_gen_command(app, run);
  add_bench_command(app, run);
  add_compare_command(app, run);
  add_capacity_command(app, run);
  add_advise_command(app, run);
  add_check_command(app, run);
  add_diff_command(app, run);
  add_render_command(app, run);
  add_report_command(app, run);
  style_help(app);

  std::vector<std::string> args(argv + 1, argv + argc);
  // `crowdprof help [COMMAND]` is `crowdprof [COMMAND] --help`.
  if (!args.empty() && args.front() == "help") {
    args.erase(args.begin());
    args.resize(std::min<size_t>(args.size(), 1));
    args.push_back("--help");
  }
  std::string word = command_word(app, args);
  std::vector<std::string> commands = command_names(app);
  if (!word.empty() && std::find(commands.begin(), commands.end(), word) == commands.end()) {
    std::string near = nearest_name(word, commands);
    // A file where the command goes: the command was left out.
    if (near.empty() && word.find('.') != std::string::npos) near = "bench " + word;
    std::cerr << "crowdprof: unknown command '" << word << "'" << (near.empty() ? "" : "; did you mean " + near + "?")
              << " (commands: " << command_list(app) << "; see crowdprof --help)\n";
    return crowdprof::kExitUsage;
  }
  try {
    std::reverse(args.begin(), args.end());  // CLI11 takes them from the back
    app.parse(args);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // One line, like every other error (CLI11 would add a second).
    std::cerr << "crowdprof: " << describe_parse_error(app, e) << "\n";
    return crowdprof::kExitUsage;
  }
  // A bad global value is refused whatever else was asked, --version too.
  for (const std::string& error : {simd_error, stores_error})
    if (!error.empty()) {
      std::cerr << "crowdprof: " << error << "\n";
      return crowdprof::kExitUsage;
    }
  if (version) {
    std::cout << crowdprof::version_line() << "\n";
    return crowdprof::kExitOk;
  }
  if (!run) {
    std::cerr << "crowdprof: no command given (commands: " << command_list(app) << "; see crowdprof --help)\n";
    return crowdprof::kExitUsage;
  }
  crowdprof::set_current_command(command_word(app, std::vector<std::string>(argv + 1, argv + argc)));
  // The command line parses: with CROWDPROF_PARSE_ONLY set, that is all (the
  // test that runs every command quoted in README and docs/ asks only this).
  if (const char* parse_only = std::getenv("CROWDPROF_PARSE_ONLY"); parse_only && *parse_only)
    return crowdprof::kExitOk;
  try {
    return run();
  } catch (...) {
    return crowdprof::report_current_exception();
  }
}

}  // namespace

int main(int argc, char** argv) {
  return after_flushing_stdout(run_command(argc, argv));
}
