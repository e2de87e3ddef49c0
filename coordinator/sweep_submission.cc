// Copyright 2026 The DCS Authors.
#include "coordinator/sweep_submission.h"

#include <yaml-cpp/yaml.h>

#include <utility>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "common/status_util.h"
#include "coordinator/run_submission.h"
#include "env/observe_mode.h"
#include "run/seeded_runs.h"
#include "run/sweep_spec_yaml.h"
#include "run/yaml_reader.h"

namespace dcs::coordinator {

absl::StatusOr<ExpandedSweep> ExpandSweep(const std::string& spec_text,
                                          const std::string& spec_name,
                                          const std::string& default_name,
                                          const std::string& request_id) {
  run::YamlReader reader(spec_name);
  DCS_ASSIGN_OR_RETURN(const YAML::Node root, reader.Load(spec_text));
  DCS_ASSIGN_OR_RETURN(run::SweepSpec spec, run::ReadSweepSpec(reader, root));
  ExpandedSweep sweep;
  SweepSubmission& submission = sweep.submission;
  submission = {.request_id = request_id,
                .name = spec.name.empty() ? default_name : spec.name,
                .spec = spec_text,
                .seeds = static_cast<int>(spec.seeds.size())};
  if (spec.study) {  // its trials and runs come as its study asks for them
    DCS_ASSIGN_OR_RETURN(StudySweepSpec study, ReadStudySweep(reader, root, std::move(spec)));
    submission.study = study.study;
    submission.study->request_id = request_id;
    submission.study->name = submission.name;
    sweep.study = std::move(study);
    return sweep;
  }
  std::vector<run::SeededRuns> trials;
  for (run::SweepTrial& trial : spec.trials) {
    const TrialRecord& record = submission.trials.emplace_back(
        TrialRecord{.condition = trial.condition,
                    .family = trial.family,
                    .observe = std::string(NameOf(env::kObserveModeNames, trial.observe))});
    DCS_RETURN_IF_ERROR(Annotate(
        CheckPlannable(trial.spec),
        absl::StrCat(spec_name, ": ", record.condition, " (", record.observe, ")")));
    trials.emplace_back(std::move(trial.spec), std::move(trial.config));
  }
  for (uint64_t seed : spec.seeds) {
    for (size_t t = 0; t < trials.size(); ++t) {
      run::RunRequest run = trials[t].Run(seed);
      submission.runs.push_back(
          {.trial = static_cast<int>(t),
           .run = SubmissionOf(run, absl::StrCat(request_id, "/", t, "/", seed))});
      sweep.requests.push_back(std::move(run));
    }
  }
  return sweep;
}

SweepRecord SweepPreview(const ExpandedSweep& sweep) {
  return {.name = sweep.submission.name,
          .seeds = sweep.submission.seeds,
          .trials = sweep.submission.trials,
          .runs_by_state = {{RunState::kQueued,
                             static_cast<int64_t>(sweep.submission.runs.size())}}};
}

}  // namespace dcs::coordinator
