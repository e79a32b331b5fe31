// crowdprof: profile skinned-crowd scenes. This file only dispatches to the
// subcommands (cli/cmd_*.cpp) and turns errors into exit statuses:
// 2 for a bad command line, 3 for a bad input file, 4 when the run fails.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "asset/errors.h"
#include "cli/child_run.h"
#include "cli/commands.h"
#include "profile/environment.h"
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
  // The SIMD target skinning runs on: the CPU's best, else CROWDPROF_SIMD, else
  // --simd (applied as soon as it is parsed, so that --version after it shows it).
  std::string simd_error;
  if (const char* from_env = std::getenv(crowdprof::kSimdEnvironmentVariable))
    simd_error = crowdprof::force_simd_target(from_env);
  app.set_version_flag("--version", [] { return crowdprof::version_line(); },
                       "Print the version, commit, build type, compiler and SIMD target on one line");
  app.add_option_function<std::string>(
         "--simd", [&](const std::string& name) { simd_error = crowdprof::force_simd_target(name); },
         "Run skinning on this SIMD target instead of the CPU's best (SCALAR, SSSE3, SSE4, AVX2, AVX3, AVX3_DL; "
         "also the environment variable CROWDPROF_SIMD)")
      ->trigger_on_parse();
  // How skinned vertices are stored (output_stores.h): CROWDPROF_STORES, else --stores.
  std::string stores_error;
  if (const char* from_env = std::getenv(crowdprof::kStoresEnvironmentVariable))
    stores_error = crowdprof::force_output_stores(from_env);
  app.add_option_function<std::string>(
      "--stores", [&](const std::string& name) { stores_error = crowdprof::force_output_stores(name); },
      "How CPU skinning writes float vertices: auto (streaming stores when a frame's output is larger than "
      "64 MiB), regular or streaming (also the environment variable CROWDPROF_STORES)");
  app.require_subcommand(1);
  app.footer("Each command lists its options: crowdprof bench --help\n\nExamples:\n  crowdprof bench scenes/thesis.json");
  std::function<int()> run;
  add_info_command(app, run);
  add_gen_command(app, run);
  add_bench_command(app, run);
  add_compare_command(app, run);
  add_capacity_command(app, run);
  add_check_command(app, run);
  add_diff_command(app, run);
  add_render_command(app, run);
  add_report_command(app, run);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line, like every other error (CLI11 would add a second).
    std::cerr << "crowdprof: " << e.what() << " (see crowdprof --help)\n";
    return crowdprof::kExitUsage;
  }
  for (const std::string& error : {simd_error, stores_error})
    if (!error.empty()) {
      std::cerr << "crowdprof: " << error << "\n";
      return crowdprof::kExitUsage;
    }
  try {
    return run ? run() : crowdprof::kExitUsage;
  } catch (...) {
    return crowdprof::report_current_exception();
  }
}

}  // namespace

int main(int argc, char** argv) { return after_flushing_stdout(run_command(argc, argv)); }
