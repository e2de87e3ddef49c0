// Copyright 2026 The DCS Authors.
#include "run/evaluation_log.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <google/protobuf/util/json_util.h>

#include "absl/strings/str_cat.h"
#include "common/atomic_file.h"
#include "common/enum_names.h"
#include "common/round_trip.h"
#include "common/status_macros.h"
#include "dcs/proto_json.h"
#include "run/appended_evaluation_log.h"

namespace dcs::run {
namespace {

constexpr char kJsonFile[] = "evaluations.json";
constexpr char kCsvFile[] = "evaluations.csv";

static_assert(v1::SPLIT_ID == static_cast<int>(actor::Split::kId) + 1);
static_assert(v1::SPLIT_OOD_LOW == static_cast<int>(actor::Split::kOodLow) + 1);
static_assert(v1::SPLIT_OOD_HIGH == static_cast<int>(actor::Split::kOodHigh) + 1);
static_assert(v1::Split_ARRAYSIZE == actor::kNumSplits + 1);

v1::Evaluation ToProto(const actor::EvaluationResult& result) {
  v1::Evaluation evaluation;
  evaluation.set_step(result.step);
  evaluation.set_updates(result.updates);
  evaluation.set_avg_combined(result.avg_combined);
  // The proto's per-split fields, in actor::Split's order.
  v1::SplitSummary* splits[] = {evaluation.mutable_id(), evaluation.mutable_ood_low(),
                                evaluation.mutable_ood_high()};
  static_assert(sizeof(splits) / sizeof(splits[0]) == actor::kNumSplits);
  for (int split = 0; split < actor::kNumSplits; ++split) {
    splits[split]->set_mean(result.split_mean[split]);
    splits[split]->set_min(result.split_min[split]);
  }
  for (const actor::ContextResult& context : result.contexts) {
    v1::ContextEvaluation* out = evaluation.add_contexts();
    out->set_split(SplitToProto(context.context.split));
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
                      NameOf(actor::kSplitNames, *SplitFromProto(context.split())), ",",
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

std::string EvaluationCsvPath(const std::string& dir) {
  return (std::filesystem::path(dir) / kCsvFile).string();
}

std::vector<EvaluationLogFile> EvaluationLogFiles(const v1::EvaluationLog& log) {
  return {{.name = kCsvFile, .contents = ToCsv(log)},
          {.name = kJsonFile, .contents = ProtoToJson(log)}};
}

absl::Status WriteEvaluationLog(const std::string& dir, const v1::EvaluationLog& log) {
  for (const EvaluationLogFile& file : EvaluationLogFiles(log)) {
    DCS_RETURN_IF_ERROR(
        WriteFileAtomically((std::filesystem::path(dir) / file.name).string(), file.contents));
  }
  return absl::OkStatus();
}

absl::StatusOr<v1::EvaluationLog> ReadEvaluationLog(const std::string& dir) {
  if (HasAppendedEvaluationLog(dir)) return ReadAppendedEvaluationLog(dir);
  const std::string path = (std::filesystem::path(dir) / kJsonFile).string();
  absl::StatusOr<std::string> json = ReadFile(path);
  if (!json.ok()) {
    return absl::NotFoundError(absl::StrCat("no evaluation log in ", dir, ": ", path));
  }
  v1::EvaluationLog log;
  if (const auto parsed = google::protobuf::util::JsonStringToMessage(*json, &log); !parsed.ok()) {
    return absl::DataLossError(
        absl::StrCat(path, " is not an evaluation log: ", parsed.message().as_string()));
  }
  for (const v1::Evaluation& evaluation : log.evaluations()) {
    DCS_RETURN_IF_ERROR(internal::CheckSplits(evaluation, path));
  }
  return log;
}

v1::Split SplitToProto(actor::Split split) {
  return static_cast<v1::Split>(static_cast<int>(split) + 1);
}

std::optional<actor::Split> SplitFromProto(int split) {
  if (split < 1 || split > actor::kNumSplits) return std::nullopt;
  return static_cast<actor::Split>(split - 1);
}

namespace internal {

absl::Status CheckSplits(const v1::Evaluation& evaluation, const std::string& path) {
  for (const v1::ContextEvaluation& context : evaluation.contexts()) {
    if (!SplitFromProto(context.split()).has_value()) {
      return absl::DataLossError(absl::StrCat(path, ": the evaluation at step ", evaluation.step(),
                                              " has a context of split ", context.split(),
                                              ", which is none of ",
                                              ListNames(actor::kSplitNames)));
    }
  }
  return absl::OkStatus();
}

}  // namespace internal

}  // namespace dcs::run
