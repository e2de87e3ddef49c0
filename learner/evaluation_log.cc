// Copyright 2026 The DCS Authors.
#include "learner/evaluation_log.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/round_trip.h"
#include "common/status_macros.h"
#include "dcs/proto_json.h"

namespace dcs::learner {
namespace {

v1::Split ToProto(actor::Split split) {
  switch (split) {
    case actor::Split::kId: return v1::SPLIT_ID;
    case actor::Split::kOodLow: return v1::SPLIT_OOD_LOW;
    case actor::Split::kOodHigh: return v1::SPLIT_OOD_HIGH;
  }
  return v1::SPLIT_UNSPECIFIED;
}

actor::Split FromProto(v1::Split split) {
  switch (split) {
    case v1::SPLIT_OOD_LOW: return actor::Split::kOodLow;
    case v1::SPLIT_OOD_HIGH: return actor::Split::kOodHigh;
    default: return actor::Split::kId;
  }
}

v1::Evaluation ToProto(const actor::EvaluationResult& result) {
  v1::Evaluation evaluation;
  evaluation.set_step(result.step);
  evaluation.set_updates(result.updates);
  evaluation.set_avg_combined(result.avg_combined);
  v1::SplitSummary* splits[] = {evaluation.mutable_id(), evaluation.mutable_ood_low(),
                                evaluation.mutable_ood_high()};
  for (int split = 0; split < 3; ++split) {
    splits[split]->set_mean(result.split_mean[split]);
    splits[split]->set_min(result.split_min[split]);
  }
  for (const actor::ContextResult& context : result.contexts) {
    v1::ContextEvaluation* out = evaluation.add_contexts();
    out->set_split(ToProto(context.context.split));
    out->set_value(context.context.value);
    out->set_mean(context.mean);
    out->set_std(context.std);
    out->mutable_returns()->Add(context.returns.begin(), context.returns.end());
    out->set_seconds(context.seconds);
  }
  return evaluation;
}

std::string ToCsv(const v1::EvaluationLog& log) {
  std::string csv = "step,updates,split,value,episodes,mean,std,seconds\n";
  for (const v1::Evaluation& evaluation : log.evaluations()) {
    for (const v1::ContextEvaluation& context : evaluation.contexts()) {
      absl::StrAppend(&csv, evaluation.step(), ",", evaluation.updates(), ",",
                      actor::SplitName(FromProto(context.split())), ",",
                      RoundTrip(context.value()), ",", context.returns_size(), ",",
                      RoundTrip(context.mean()), ",", RoundTrip(context.std()), ",",
                      RoundTrip(context.seconds()), "\n");
    }
  }
  return csv;
}

}  // namespace

v1::EvaluationLog MakeEvaluationLog(const RunSpec& spec,
                                    const std::vector<actor::EvaluationResult>& evaluations,
                                    const std::vector<int64_t>& stage_boundaries, bool complete) {
  v1::EvaluationLog log;
  log.set_env(spec.env);
  log.set_feature(spec.feature);
  log.set_seed(spec.seed);
  log.set_complete(complete);
  log.set_last(evaluations.empty() ? std::nan("") : evaluations.back().avg_combined);
  log.set_best_anytime(std::nan(""));
  log.set_best_anytime_index(-1);
  for (size_t i = 0; i < evaluations.size(); ++i) {
    const actor::EvaluationResult& evaluation = evaluations[i];
    *log.add_evaluations() = ToProto(evaluation);
    const bool at_end = complete && i + 1 == evaluations.size();
    const bool candidate =
        stage_boundaries.empty() || at_end ||
        std::find(stage_boundaries.begin(), stage_boundaries.end(), evaluation.step) !=
            stage_boundaries.end();
    if (candidate &&
        (log.best_anytime_index() < 0 || evaluation.avg_combined > log.best_anytime())) {
      log.set_best_anytime(evaluation.avg_combined);
      log.set_best_anytime_index(static_cast<int>(i));
    }
  }
  return log;
}

absl::Status WriteEvaluationLog(const std::string& dir, const v1::EvaluationLog& log) {
  const std::filesystem::path root(dir);
  DCS_RETURN_IF_ERROR(WriteFileAtomically(root / "evaluations.csv", ToCsv(log)));
  return WriteFileAtomically(root / "evaluations.json", ProtoToJson(log));
}

}  // namespace dcs::learner
