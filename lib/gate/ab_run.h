// check --against BASE, the A/B of two builds (gate/ab_check.h judges it): the
// part of check's runner (gate/check_run.h) that runs both builds as processes
// in ABBA groups. Internal to the runner.
#pragma once

#include "gate/check_plan.h"
#include "gate/check_run.h"

namespace crowdprof {

// Runs the A/B `r` asks for under `plan` and returns its outcome.
CheckOutcome run_ab(const CheckRun& r, const CheckPlan& plan);

}  // namespace crowdprof
