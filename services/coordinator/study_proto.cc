// Copyright 2026 The DCS Authors.
#include "services/coordinator/study_proto.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "common/enum_names.h"
#include "common/status_macros.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

template <typename E, size_t N>
absl::StatusOr<E> FromName(const EnumName<E> (&table)[N], const std::string& name,
                           absl::string_view what) {
  const std::optional<E> value = FindByName(table, name);
  if (!value.has_value()) {
    return absl::InvalidArgumentError(absl::StrCat("unknown ", what, " '", name, "'"));
  }
  return *value;
}

}  // namespace

v1::StudyTrial StudyTrialToProto(const coordinator::StudyTrial& trial) {
  v1::StudyTrial proto;
  proto.set_number(trial.number);
  proto.set_state(std::string(NameOf(coordinator::kTrialStateNames, trial.state)));
  if (!std::isnan(trial.value)) proto.set_value(trial.value);
  for (const auto& [name, value] : trial.values) (*proto.mutable_values())[name] = value;
  for (const auto& [step, value] : trial.reported) (*proto.mutable_reported())[step] = value;
  return proto;
}

absl::StatusOr<coordinator::StudyTrial> StudyTrialFromProto(const v1::StudyTrial& proto) {
  coordinator::StudyTrial trial{.number = proto.number(),
                                .value = proto.has_value() ? proto.value() : std::nan("")};
  DCS_ASSIGN_OR_RETURN(trial.state,
                       FromName(coordinator::kTrialStateNames, proto.state(), "trial state"));
  trial.values.insert(proto.values().begin(), proto.values().end());
  trial.reported.insert(proto.reported().begin(), proto.reported().end());
  return trial;
}

v1::Study StudyToProto(const coordinator::StudyRecord& study) {
  const coordinator::StudySubmission& s = study.submission;
  v1::Study proto;
  proto.set_study_id(study.id);
  proto.set_name(s.name);
  proto.set_space(s.space);
  proto.set_sampler(std::string(NameOf(coordinator::kSamplerKindNames, s.sampler)));
  proto.set_seed(s.seed);
  proto.set_direction(std::string(NameOf(coordinator::kDirectionNames, s.direction)));
  v1::TpeOptions& tpe = *proto.mutable_tpe();
  tpe.set_startup_trials(s.tpe.startup_trials);
  tpe.set_ei_candidates(s.tpe.ei_candidates);
  tpe.set_multivariate(s.tpe.parzen.multivariate);
  tpe.set_group(s.tpe.group);
  tpe.set_constant_liar(s.tpe.constant_liar);
  for (const auto& [state, count] : study.trials_by_state) {
    (*proto.mutable_trials_by_state())[std::string(NameOf(coordinator::kTrialStateNames, state))] =
        count;
  }
  if (study.best.has_value()) *proto.mutable_best() = StudyTrialToProto(*study.best);
  *proto.mutable_create_time() = TimeToProto(study.created_at);
  proto.set_sweep_id(study.sweep_id);
  const coordinator::PrunerOptions& pruner = s.pruner;
  v1::PrunerOptions& wire = *proto.mutable_pruner();
  wire.set_kind(std::string(NameOf(coordinator::kPrunerKindNames, pruner.kind)));
  wire.set_percentile(pruner.median.percentile);
  wire.set_startup_trials(pruner.median.startup_trials);
  wire.set_warmup_steps(pruner.median.warmup_steps);
  wire.set_interval_steps(pruner.median.interval_steps);
  wire.set_min_trials(pruner.median.min_trials);
  if (pruner.halving.min_resource.has_value()) wire.set_min_resource(*pruner.halving.min_resource);
  wire.set_reduction_factor(pruner.halving.reduction_factor);
  wire.set_min_early_stopping_rate(pruner.halving.min_early_stopping_rate);
  wire.set_bootstrap_count(pruner.halving.bootstrap_count);
  return proto;
}

absl::StatusOr<coordinator::StudyRecord> StudyFromProto(const v1::Study& proto) {
  coordinator::StudyRecord study{.id = proto.study_id()};
  study.sweep_id = proto.sweep_id();
  coordinator::StudySubmission& s = study.submission;
  s.name = proto.name();
  s.space = proto.space();
  DCS_ASSIGN_OR_RETURN(s.sampler,
                       FromName(coordinator::kSamplerKindNames, proto.sampler(), "sampler"));
  s.seed = proto.seed();
  DCS_ASSIGN_OR_RETURN(s.direction,
                       FromName(coordinator::kDirectionNames, proto.direction(), "direction"));
  s.tpe.startup_trials = proto.tpe().startup_trials();
  s.tpe.ei_candidates = proto.tpe().ei_candidates();
  s.tpe.parzen.multivariate = proto.tpe().multivariate();
  s.tpe.group = proto.tpe().group();
  s.tpe.constant_liar = proto.tpe().constant_liar();
  for (const auto& [name, count] : proto.trials_by_state()) {
    DCS_ASSIGN_OR_RETURN(const coordinator::TrialState state,
                         FromName(coordinator::kTrialStateNames, name, "trial state"));
    study.trials_by_state.emplace_back(state, count);
  }
  if (proto.has_best()) {
    DCS_ASSIGN_OR_RETURN(study.best, StudyTrialFromProto(proto.best()));
  }
  study.created_at = TimeFromProto(proto.create_time());
  const v1::PrunerOptions& wire = proto.pruner();
  coordinator::PrunerOptions& pruner = s.pruner;
  DCS_ASSIGN_OR_RETURN(pruner.kind, FromName(coordinator::kPrunerKindNames, wire.kind(), "pruner"));
  pruner.median = {.percentile = wire.percentile(),
                   .startup_trials = wire.startup_trials(),
                   .warmup_steps = wire.warmup_steps(),
                   .interval_steps = wire.interval_steps(),
                   .min_trials = wire.min_trials()};
  if (wire.has_min_resource()) pruner.halving.min_resource = wire.min_resource();
  pruner.halving.reduction_factor = wire.reduction_factor();
  pruner.halving.min_early_stopping_rate = wire.min_early_stopping_rate();
  pruner.halving.bootstrap_count = wire.bootstrap_count();
  return study;
}

}  // namespace dcs::services
