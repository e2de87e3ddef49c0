// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_FUZZ_FUZZ_CHECK_H_
#define DCS_TESTS_FUZZ_FUZZ_CHECK_H_

// What a fuzz target asserts beyond "no crash, no leak, no sanitizer report": a promise of the
// code under test (an error's code, a round trip) that the input broke is reported as a crash,
// so that libFuzzer stops and saves the input. Thread-safe.

#include <cstdio>
#include <cstdlib>
#include <string>

#include "absl/status/status.h"

// Aborts, naming the check, the file and line and `status` (an absl::Status: what the code
// under test returned), unless `condition` holds.
#define DCS_FUZZ_CHECK(condition, status)                                                      \
  do {                                                                                         \
    if (!(condition)) {                                                                        \
      const std::string dcs_fuzz_status = (status).ToString();                                 \
      std::fprintf(stderr, "%s:%d: fuzz check failed: %s\n  status: %s\n", __FILE__, __LINE__, \
                   #condition, dcs_fuzz_status.c_str());                                       \
      std::abort();                                                                            \
    }                                                                                          \
  } while (false)

#endif  // DCS_TESTS_FUZZ_FUZZ_CHECK_H_
