// The host C/C++ compiler the tests that compile emitted headers use (SAAGEN_TEST_CXX_COMPILER,
// the one that built them). A device machine that runs binaries built elsewhere may have none:
// such a test skips there with this reason rather than failing.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace saagen::test {

// Whether `compiler` runs here (`compiler --version` exits 0).
inline bool host_compiler_runs(const std::string& compiler) {
  return std::system(("\"" + compiler + "\" --version > /dev/null 2>&1").c_str()) == 0;
}

}  // namespace saagen::test

// In a TEST body: skip, naming the compiler, when it does not run on this machine.
#define SAAGEN_SKIP_WITHOUT_HOST_COMPILER(compiler)                                                                          \
  do {                                                                                                                       \
    if (!saagen::test::host_compiler_runs(compiler))                                                                         \
      GTEST_SKIP() << "no host C/C++ compiler here (" << (compiler)                                                          \
                   << " does not run): this test compiles the emitted header, which needs the machine that built the tests"; \
  } while (false)
