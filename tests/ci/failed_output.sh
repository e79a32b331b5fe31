#!/usr/bin/env bash
# failed_output.sh LOG: each failed test's own output, from a log of
# `ctest --output-on-failure`, with gtest's RUN/OK chatter left out. The CI
# stages print it after ctest's summary, so a red CI says why a test failed,
# not only which (the summary names it; its output is hundreds of lines up).
set -euo pipefail
awk '
  /^ *[0-9]+\/[0-9]+ Test +#[0-9]+: / { show = ($0 !~ / Passed /); if (show) print; next }
  /^ *Start +[0-9]+: |^[0-9]+% tests passed/ { show = 0 }
  show && !/^$|^\[  FAILED  \] [0-9]+ tests?, listed below|^ *[0-9]+ FAILED TESTS?$|^\[ *(RUN|OK|==========|----------|PASSED) *\]|^Running main|^Note: Google Test filter|^Test command:|^Working Directory:|^Environment variables:|^Test timeout computed/
' "$1" | head -n "${FAILED_OUTPUT_LINES:-80}"
