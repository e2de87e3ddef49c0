// Copyright 2026 The DCS Authors.
// Fuzzes the run config parser, run::ParseRunSpecYaml (run/run_spec_yaml.h), which reads what
// `dcs train --config` and `dcs submit` are given. The input is a run config's text; the seeds
// are the configs of configs/.
// Asserts: every input gives a spec or an INVALID_ARGUMENT error (the header's only error), and
// a spec it accepts passes ValidateRunSpec on its own.

#include <cstddef>
#include <cstdint>

#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "run/run_spec_yaml.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const absl::string_view text(reinterpret_cast<const char*>(data), size);
  const absl::StatusOr<dcs::run::RunSpec> spec = dcs::run::ParseRunSpecYaml(text, "fuzz.yaml");
  if (!spec.ok()) {
    DCS_FUZZ_CHECK(absl::IsInvalidArgument(spec.status()), spec.status());
    return 0;
  }
  const absl::Status valid = dcs::run::ValidateRunSpec(*spec);
  DCS_FUZZ_CHECK(valid.ok(), valid);
  return 0;
}
