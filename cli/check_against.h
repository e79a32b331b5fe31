// `check --against BASE`: an A/B of two builds at the same moment
// (gate/ab_check.h). Both builds are run as processes of their own, the
// current one as well (this binary), with the same bench options, in ABBA
// groups; the verdict compares their paired ratios.
#pragma once

#include <string>
#include <vector>

#include "cli/bench_options.h"
#include "gate/ab_check.h"

struct AgainstRequest {
  std::string base_binary;
  const BenchCliOptions* bench = nullptr;  // the options given on the command line, handed to both builds
  crowdprof::AbOptions gate;
  size_t groups = crowdprof::kAbGroups;
  std::vector<std::string> gate_arguments;  // --metric, --tolerance ... as given: for the reproducing command
  std::string json, junit, markdown;  // outputs, when named
  std::string html;  // the last run of each build side by side (the verdict is in the others)
};

// The base binary is checked before anything runs: InputError naming it when
// it is missing, not a regular executable file, not crowdprof, or when a
// one-frame run of the same options gives no result this build reads.
// Returns the process's exit status: 0, or 1 when a metric is slower or the
// work changed.
int check_against(const AgainstRequest& request);
