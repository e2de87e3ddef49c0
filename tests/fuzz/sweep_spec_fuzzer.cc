// Copyright 2026 The DCS Authors.
// Fuzzes the sweep spec parser as `dcs submit` reaches it on the coordinator,
// coordinator::ExpandSweep (coordinator/sweep_submission.h): run::ParseSweepSpecYaml, and
// ParseStudySweepYaml for a spec with a `study:` block, then every run checked as a run
// submitted alone. The input is a sweep spec's text; the seeds are the sweeps of configs/.
// Asserts: every input gives a sweep or an INVALID_ARGUMENT error (the header's only error);
// an accepted plain sweep has one run per trial and seed, and each run's stored config reads
// back as a run config, as the learner that takes it will read it.

#include <cstddef>
#include <cstdint>
#include <string>

#include "absl/status/statusor.h"
#include "coordinator/sweep_table.h"
#include "coordinator/sweep_submission.h"
#include "run/run_spec_yaml.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const absl::StatusOr<dcs::coordinator::ExpandedSweep> sweep =
      dcs::coordinator::ExpandSweep(text, "fuzz.yaml", "fuzz", "request-1");
  if (!sweep.ok()) {
    DCS_FUZZ_CHECK(absl::IsInvalidArgument(sweep.status()), sweep.status());
    return 0;
  }
  const dcs::coordinator::SweepSubmission& submission = sweep->submission;
  if (submission.study.has_value()) return 0;  // its runs come as its study asks for them
  DCS_FUZZ_CHECK(submission.runs.size() == submission.trials.size() * submission.seeds,
                 absl::OkStatus());
  for (const dcs::coordinator::SweepSubmission::Run& run : submission.runs) {
    const absl::StatusOr<dcs::run::RunSpec> spec =
        dcs::run::ParseRunSpecYaml(run.run.config, "stored config");
    DCS_FUZZ_CHECK(spec.ok(), spec.status());
  }
  return 0;
}
