// Copyright 2026 The DCS Authors.
// Fuzzes the coordinator's store readers (coordinator/store.h) on a database file that is
// not what the store wrote: the input is the whole file, which Store::Open opens (and
// migrates), then every read method is called on every run, sweep, study and evaluation it
// lists. The seeds are stores written by test runs (a run with evaluations and checkpoints, a
// sweep, a study, a study sweep), all but one rewritten with 512-byte pages to be small.
// Asserts: every call returns a value or an absl::Status (no crash, no exception escaping, no
// sanitizer report), and an error is one the store documents for a file it cannot trust
// (DATA_LOSS, INTERNAL, FAILED_PRECONDITION), or NOT_FOUND for an id that is not there.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "coordinator/store.h"
#include "tests/fuzz/fuzz_check.h"
#include "tests/fuzz/scratch_dir.h"

namespace dcs::fuzz {
namespace {

using coordinator::Store;

// A fixed time: what Open and the reads do must depend on the file alone.
const absl::Time kNow = absl::FromUnixSeconds(1'800'000'000);

// Checks that `status` is one a reader may give for a damaged file, and returns whether it is
// OK (the value can be used).
bool Readable(const absl::Status& status) {
  DCS_FUZZ_CHECK(status.ok() || absl::IsDataLoss(status) || absl::IsInternal(status) ||
                     absl::IsFailedPrecondition(status) || absl::IsNotFound(status),
                 status);
  return status.ok();
}

void ReadRun(Store& store, const coordinator::RunRecord& run) {
  if (absl::StatusOr<coordinator::RunRecord> again = store.runs().GetRun(run.id);
      Readable(again.status())) {
    DCS_FUZZ_CHECK(again->id == run.id, absl::OkStatus());
  }
  Readable(store.checkpoints().ListCheckpoints(run.id).status());
  for (int64_t version : {int64_t{0}, int64_t{1}, run.progress.policy_version}) {
    Readable(store.evaluations().GetEvaluation(run.id, version).status());
  }
}

void ReadEverything(Store& store) {
  if (absl::StatusOr<std::vector<coordinator::RunRecord>> runs = store.runs().ListRuns();
      Readable(runs.status())) {
    for (const coordinator::RunRecord& run : *runs) ReadRun(store, run);
  }
  Readable(store.runs().GetRun("run-1").status());
  Readable(store.sweeps().ListOpenSweeps().status());
  if (absl::StatusOr<std::vector<coordinator::SweepRecord>> sweeps = store.sweeps().ListSweeps();
      Readable(sweeps.status())) {
    for (const coordinator::SweepRecord& sweep : *sweeps) {
      Readable(store.sweeps().GetSweep(sweep.id).status());
      Readable(store.sweeps().ListSweepRuns(sweep.id).status());
    }
  }
  if (absl::StatusOr<std::vector<coordinator::StudyRecord>> studies = store.studies().ListStudies();
      Readable(studies.status())) {
    for (const coordinator::StudyRecord& study : *studies) {
      Readable(store.studies().GetStudy(study.id).status());
      Readable(store.studies().ListStudyTrials(study.id).status());
    }
  }
  Readable(store.Counts().status());
}

void FuzzStore(const uint8_t* data, size_t size) {
  const std::string path = absl::StrCat(ScratchDir(), "/coordinator.db");
  std::error_code error;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::filesystem::remove(path + suffix, error);
  }
  const absl::Status written =
      WriteFileAtomically(path, std::string(reinterpret_cast<const char*>(data), size));
  DCS_FUZZ_CHECK(written.ok(), written);
  absl::StatusOr<std::unique_ptr<Store>> store = Store::Open(path, {}, kNow);
  if (!Readable(store.status())) return;
  ReadEverything(**store);
}

}  // namespace
}  // namespace dcs::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dcs::fuzz::FuzzStore(data, size);
  return 0;
}
