// Copyright 2026 The DCS Authors.
#ifndef DCS_RUN_APPENDED_EVALUATION_LOG_H_
#define DCS_RUN_APPENDED_EVALUATION_LOG_H_

// A run's evaluation log as the coordinator keeps it: appended at each checkpoint with the
// evaluations made since the last, so that neither the wire nor the coordinator carries the
// whole log each time. In the run's directory:
//   evaluations.jsonl          one dcs.v1.Evaluation per line, in protobuf's JSON, appended
//                              and fsync'd
//   evaluations.summary.json   a dcs.v1.AppendedEvaluationLog: the log's other fields and how
//                              many lines (and bytes) of evaluations.jsonl are the log's,
//                              rewritten atomically after each append: the append's commit
// A crash mid-append leaves lines past the summary's count (the last one perhaps torn): readers
// never see them and the next append cuts them off. Readers read it through ReadEvaluationLog
// (run/evaluation_log.h), and users get evaluations.json and .csv made from it
// (EvaluationLogFiles), as `dcs train` writes them.
// Thread-compatible: one writer per directory (the run's learner lease holder).

#include <cstdint>
#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "dcs/v1/evaluation.pb.h"

namespace dcs::run {

// `log` with only its evaluations from index `first` on (none if it has no more): what a
// learner sends with a checkpoint when the coordinator has the first `first`.
v1::EvaluationLog EvaluationLogSince(const v1::EvaluationLog& log, int64_t first);

// Appends to the log in `dir` (created if missing) the evaluations of `since`, the run's log
// from evaluation `first` on (EvaluationLogSince), and takes its other fields. Evaluations the
// log already holds are not appended again: a learner resumed from a checkpoint older than the
// log, or sending a checkpoint again, makes the same evaluations (runs are deterministic). A
// log that already holds more than `first` + all of `since` is left as it is. A log of
// WriteEvaluationLog's (a directory of an older coordinator) is first turned into this form.
// DATA_LOSS if the log holds fewer than `first` evaluations (some would be missing), or naming
// its summary (or the older log) if that does not read; its lines are not read (so a damaged
// line is found by readers, not here). Errors of writing name the file
// (RESOURCE_EXHAUSTED for a full disk), and the log is then as before.
absl::Status AppendEvaluationLog(const std::string& dir, int64_t first,
                                 const v1::EvaluationLog& since);

// True if `dir` holds a log of AppendEvaluationLog's.
bool HasAppendedEvaluationLog(const std::string& dir);

// That log. NOT_FOUND if there is none; DATA_LOSS naming the file and line of what does not
// read, or if evaluations.jsonl is shorter than its summary says.
absl::StatusOr<v1::EvaluationLog> ReadAppendedEvaluationLog(const std::string& dir);

}  // namespace dcs::run

#endif  // DCS_RUN_APPENDED_EVALUATION_LOG_H_
