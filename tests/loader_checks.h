// Checks shared by the loader's tests: a bad file must be refused the same way by
// the library (one InputError) and by the CLI (exit 3, one line on stderr).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "asset/gltf_loader.h"
#include "test_support.h"

namespace crowdprof::test {

// The message load_gltf gives for `file`, or a test failure if it loads or throws
// anything but InputError.
inline std::string input_error(const std::string& file) {
  try {
    load_gltf(file);
    ADD_FAILURE() << file << " loaded, but should have been refused";
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << file << " threw something other than InputError: " << e.what();
  }
  return "";
}

// `file` is refused with a message "<file>: <problem>" on one line, the problem
// holding every one of `words`; `crowdprof info` exits 3 with that line on stderr.
inline void expect_bad_input(const std::string& file, const std::vector<std::string>& words) {
  SCOPED_TRACE("refusing " + file);
  std::string message = input_error(file);
  EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  for (const std::string& word : words)
    EXPECT_NE(message.find(word), std::string::npos) << "no \"" << word << "\" in: " << message;

  CliResult cli = run_cli("info " + shell_quoted(file));
  EXPECT_EQ(cli.status, 3) << cli.err;
  EXPECT_EQ(cli.out, "");
  EXPECT_EQ(std::count(cli.err.begin(), cli.err.end(), '\n'), 1) << cli.err;
  EXPECT_EQ(cli.err, "crowdprof: " + message + "\n");
}

}  // namespace crowdprof::test
