// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_submission.h"

#include <utility>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "coordinator/run_submission.h"
#include "coordinator/study_sweep_spec.h"
#include "env/observe_mode.h"
#include "run/sweep_spec_yaml.h"

namespace dcs::coordinator {

absl::StatusOr<ExpandedSweep> ExpandSweep(const std::string& spec_text,
                                          const std::string& spec_name,
                                          const std::string& default_name,
                                          const std::string& request_id) {
  absl::StatusOr<run::SweepSpec> spec = run::ParseSweepSpecYaml(spec_text, spec_name);
  if (!spec.ok()) return spec.status();
  ExpandedSweep sweep;
  SweepSubmission& submission = sweep.submission;
  submission = {.request_id = request_id,
                .name = spec->name.empty() ? default_name : spec->name,
                .spec = spec_text,
                .seeds = static_cast<int>(spec->seeds.size())};
  if (spec->study) {  // its trials and runs come as its study asks for them
    absl::StatusOr<StudySweepSpec> study = ParseStudySweepYaml(spec_text, spec_name);
    if (!study.ok()) return study.status();
    submission.study = std::move(study->study);
    submission.study->request_id = request_id;
    submission.study->name = submission.name;
    return sweep;
  }
  for (const run::SweepTrial& trial : spec->trials) {
    submission.trials.push_back({.condition = trial.condition,
                                 .family = trial.family,
                                 .observe = std::string(NameOf(env::kObserveModeNames,
                                                               trial.observe))});
  }
  for (uint64_t seed : spec->seeds) {
    for (size_t t = 0; t < spec->trials.size(); ++t) {
      const TrialRecord& trial = submission.trials[t];
      const std::string trial_name = absl::StrCat(trial.condition, " (", trial.observe, ")");
      absl::StatusOr<run::RunRequest> run = CheckSubmittedRun(
          spec->trials[t].config, absl::StrCat(spec_name, ": ", trial_name), seed);
      if (!run.ok()) return run.status();
      submission.runs.push_back(
          {.trial = static_cast<int>(t),
           .run = SubmissionOf(*run, absl::StrCat(request_id, "/", t, "/", seed))});
      sweep.requests.push_back(*std::move(run));
    }
  }
  return sweep;
}

}  // namespace dcs::coordinator
