// Copyright 2026 The DCS Authors.
#ifndef DCS_COORDINATOR_RUN_STORE_H_
#define DCS_COORDINATOR_RUN_STORE_H_

// The coordinator's durable state: runs, their leases, their evaluations (jobs for actors and
// their results) and their checkpoint index, in one SQLite
// file (WAL, synchronous=FULL, schema versioned by PRAGMA user_version with forward-only
// migrations: coordinator/store_schema.h). Every call is one transaction and returns after it
// committed, so whatever a caller acknowledges on the strength of a call survives a crash.
//
// Leases (DESIGN.md §5). Each run has one learner lease (slot kLearnerSlot) and one lease per
// env slot. A lease is free or held by a worker until a deadline; the holder renews it before
// the deadline; a lapsed lease goes back to the queue (ExpireLeases, which every Acquire runs
// first). Each grant raises the lease's epoch, and every call a holder makes names the epoch it
// was granted, so a worker that comes back after its lease moved is refused
// (FAILED_PRECONDITION), never counted twice. When a run's learner lease is granted anew, its
// slot leases are freed: they pointed at the old learner. Evaluation jobs are leased the same
// way, one per evaluation context; their results are kept, the policy they evaluated is
// dropped once every context is in. A grid evaluation (a client's, `dcs eval --on-actors`) is
// an evaluation of its own kind: one job per cell of its grid, under a negative policy version.
//
// Numeric libraries (DESIGN.md §4): a run remembers the numeric fingerprint of the first
// learner that took it and of the first actor that stepped one of its slots; only workers
// with the same fingerprint as their role's get its leases.
//
// Times are passed in (tests drive the clock). Thread-safe: one connection behind a mutex.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/strings/string_view.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/time.h"
#include "absl/types/span.h"
#include "common/enum_names.h"
#include "coordinator/pruners.h"
#include "coordinator/run_state.h"
#include "coordinator/sampler.h"
#include "coordinator/tpe_sampler.h"
#include "run/lease_key.h"
#include "run/worker_reports.h"

namespace SQLite {
class Database;
}  // namespace SQLite

namespace dcs::coordinator {

// Leases and what workers report of runs, in the words the workers use too.
using run::ContextReturns;
using run::kLearnerSlot;
using run::LeaseKey;
using run::RunProgress;

// A run as submitted.
struct RunSubmission {
  std::string request_id;  // client-chosen; a repeated id returns the run it created
  std::string config;      // the run config (YAML), with the seed applied
  uint64_t seed = 0;
  std::string env;
  int n_envs = 1;
  int64_t total_timesteps = 0;
};

struct RunRecord {
  std::string id;  // "run-<n>"
  RunSubmission submission;
  RunState state = RunState::kQueued;
  std::string error;     // why it failed or was cancelled
  std::string learner_numerics;  // the numeric fingerprint of its learners
  std::string actor_numerics;    // of its actors
  RunProgress progress;
  std::string checkpoint;  // the latest checkpoint's name; empty before the first
  absl::Time created_at;
  absl::Time updated_at;
  std::string sweep_id;      // the sweep it belongs to ("sweep-<n>"); empty for a run alone
  std::optional<int> trial;  // its trial's index in that sweep
};

// A run leased to a learner.
struct LearnerLease {
  LeaseKey key;
  RunRecord run;
  // Its trial's condition and observation mode (TrialRecord), empty for a run alone: what the
  // learner labels the run's metrics with.
  std::string condition;
  std::string observe;
};

// An env slot leased to an actor, with where the run's learner listens.
struct SlotLease {
  LeaseKey key;
  std::string learner_address;
  int64_t learner_epoch = 0;
  uint64_t seed = 0;
  std::string config;
};

// An evaluation a run's learner hands over (DESIGN.md §3): the policy of `policy_version`,
// evaluated at training step `step` on each of the run's `contexts` evaluation contexts, with
// `episodes` episodes each. One job per context goes to actors.
struct EvaluationRequest {
  int64_t policy_version = 0;
  int64_t step = 0;
  int contexts = 0;
  int episodes = 0;
  std::string weights;  // the policy, serialised by the caller; opaque here
};

// A grid evaluation a client hands over (`dcs eval --on-actors`): a policy of run `run_id`
// evaluated in each of `cells` cells of a grid of contexts, `episodes` episodes each.
struct GridEvaluationRequest {
  std::string request_id;  // client-chosen; a repeated id returns the evaluation it created
  std::string run_id;
  int cells = 0;
  int episodes = 0;
  std::string grid;     // the grid's axes and seed, serialised by the caller; opaque here
  std::string weights;  // the policy, serialised by the caller; opaque here
};

// Names one evaluation job as its holder was granted it.
struct EvaluationJobKey {
  std::string run_id;
  int64_t policy_version = 0;
  int context = 0;
  int64_t epoch = 0;
};

// Jobs of one evaluation leased to an actor together, with what it needs to run them.
struct EvaluationGrant {
  std::vector<EvaluationJobKey> jobs;  // of one run and policy version, by context
  std::string config;                  // the run's, its seed applied
  int episodes = 0;
  std::string weights;
  // For cells of a grid evaluation, its grid (GridEvaluationRequest::grid: the jobs' contexts
  // are its cells); empty for a run's own evaluation.
  std::string grid;
};

// A job's result as its holder delivers it.
struct JobResult {
  EvaluationJobKey job;
  ContextReturns result;
};

// How an evaluation stands: `results` holds every context's, in context order, once `done`
// reaches `contexts`, and nothing before.
struct EvaluationProgress {
  int contexts = 0;
  int done = 0;
  std::vector<ContextReturns> results;
};

struct CheckpointRecord {
  std::string name;
  int64_t timesteps = 0;
  std::string sha256;  // of the checkpoint's MANIFEST
};

// Counts for metrics.
// A sweep that has work ahead: runs queued or running, or (a study sweep) trials to add.
struct ActiveSweepCounts {
  std::string sweep_id;
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  int64_t steps_remaining = 0;  // environment steps its queued and running runs have left
};

struct StoreCounts {
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  int64_t free_learner_leases = 0;  // runs waiting for a learner
  int64_t free_slot_leases = 0;     // slots of running runs waiting for an actor
  // Evaluation jobs waiting for an actor: of running runs, and cells of grid evaluations.
  int64_t free_evaluation_jobs = 0;
  std::vector<ActiveSweepCounts> active_sweeps;  // in sweep order
};

// One trial of a sweep: a condition in one observation mode (run/sweep_spec.h), or in a study
// sweep a trial of its study (its search, or its retrain with more seeds).
struct TrialRecord {
  std::string condition;
  std::string family;   // "static", a schedule family, or "multi_stage"
  std::string observe;  // none | initial | live
  std::optional<int64_t> study_trial;  // the study trial it trains, in a study sweep
  bool retrain = false;                // a study trial retrained after the search
};

// The samplers a study may use (coordinator/sampler.h).
enum class SamplerKind { kTpe, kRandom };
inline constexpr EnumName<SamplerKind> kSamplerKindNames[] = {{SamplerKind::kTpe, "tpe"},
                                                              {SamplerKind::kRandom, "random"}};
static_assert(InEnumOrder(kSamplerKindNames));

// A study as created: a search space, an objective's direction and a sampler
// (shared/spec/tpe.md).
struct StudySubmission {
  std::string request_id;  // client-chosen; a repeated id returns the study it created
  std::string name;
  std::string space;  // the search space's YAML (run/search_space_yaml.h)
  SamplerKind sampler = SamplerKind::kTpe;
  uint64_t seed = 0;
  Direction direction = Direction::kMinimize;
  TpeOptions tpe;  // for SamplerKind::kTpe (its ParzenOptions beyond `multivariate` are fixed)
  PrunerOptions pruner;
};

// A sweep as submitted: its trials and one run per trial and seed.
struct SweepSubmission {
  std::string request_id;  // client-chosen; a repeated id returns the sweep it created
  std::string name;
  std::string spec;        // the spec's text as submitted
  int seeds = 0;           // runs per trial
  std::vector<TrialRecord> trials;
  struct Run {
    int trial = 0;  // index into `trials`
    RunSubmission run;
  };
  // Queued in this order (and so started in it, within the sweep's fair share): seed-major,
  // so a sweep's early results cover every trial.
  std::vector<Run> runs;
  // A study sweep (coordinator/study_sweep.h): the study it drives, created with it. Its trials
  // and runs are added as the study asks for them (AddSweepTrial), so it has none at first.
  std::optional<StudySubmission> study;
};

struct SweepRecord {
  std::string id;  // "sweep-<n>"
  std::string request_id;
  std::string name;
  std::string spec;
  int seeds = 0;
  std::vector<TrialRecord> trials;
  SweepState state = SweepState::kQueued;  // derived from its runs and `open` (SweepStateOf)
  std::vector<std::pair<RunState, int64_t>> runs_by_state;  // every state, zeros included
  std::string study_id;  // the study it drives ("study-<n>"); empty for a plain sweep
  bool open = false;     // a study sweep that will add trials (until CloseSweep)
  absl::Time created_at;
  absl::Time updated_at;
};

struct StudyRecord {
  std::string id;  // "study-<n>"
  StudySubmission submission;
  std::string sweep_id;  // the study sweep that asks and tells it; empty for ask-and-tell
  std::vector<std::pair<TrialState, int64_t>> trials_by_state;  // every state, zeros included
  std::optional<StudyTrial> best;  // the best complete trial (the first of equals)
  absl::Time created_at;
};

// What a backup of the store holds (RunStore::Backup).
struct BackupCounts {
  int64_t runs = 0;
  int64_t sweeps = 0;
  int64_t studies = 0;
};

struct RunStoreOptions {
  absl::Duration lease_duration = absl::Seconds(10);
};

class RunStore {
 public:
  // Opens (creating) the database at `path` and migrates it to the current schema.
  // Leases held when the previous coordinator stopped get a full lease_duration from `now`, so
  // their holders can renew before anything moves. FAILED_PRECONDITION for a database written by
  // a newer DCS (its schema version is unknown); INTERNAL naming the file for SQLite errors.
  static absl::StatusOr<std::unique_ptr<RunStore>> Open(const std::string& path,
                                                        RunStoreOptions options, absl::Time now);
  ~RunStore();

  RunStore(const RunStore&) = delete;
  RunStore& operator=(const RunStore&) = delete;

  // Queues a run (or returns the one `submission.request_id` already created).
  // INVALID_ARGUMENT for an empty request id or config, or n_envs < 1.
  absl::StatusOr<RunRecord> SubmitRun(const RunSubmission& submission, absl::Time now);

  // NOT_FOUND for an unknown id.
  absl::StatusOr<RunRecord> GetRun(absl::string_view run_id);
  // Every run, oldest first.
  absl::StatusOr<std::vector<RunRecord>> ListRuns();

  // Cancels a queued or running run and frees its leases. NOT_FOUND, or FAILED_PRECONDITION if
  // it already ended.
  absl::StatusOr<RunRecord> CancelRun(absl::string_view run_id, absl::Time now);

  // Sweeps (coordinator/sweep_store.cc). Queues a sweep's runs, all of them or (on an error)
  // none, or returns the sweep `submission.request_id` already created. A study sweep is
  // created open, with its study (named as the sweep, its request id the sweep's) and no trials.
  // INVALID_ARGUMENT for an empty request id, no trials (in a plain sweep), seeds < 1, a run
  // naming no trial, a run SubmitRun refuses, or a study CreateStudy refuses.
  absl::StatusOr<SweepRecord> SubmitSweep(const SweepSubmission& submission, absl::Time now);
  // Adds a trial of study trial `trial.study_trial` and its runs to the open study sweep, all of
  // it or nothing, and returns its runs in `runs`' order; a trial already added (the same study
  // trial, retrain or not) is not added again, and its runs are returned. INVALID_ARGUMENT for a
  // trial without a study trial or with no runs, or runs SubmitRun refuses; NOT_FOUND;
  // FAILED_PRECONDITION if the sweep is not open.
  absl::StatusOr<std::vector<RunRecord>> AddSweepTrial(absl::string_view sweep_id,
                                                       const TrialRecord& trial,
                                                       const std::vector<RunSubmission>& runs,
                                                       absl::Time now);
  // The study sweep will add no more trials. NOT_FOUND; idempotent.
  absl::Status CloseSweep(absl::string_view sweep_id, absl::Time now);
  // The open study sweeps, oldest first.
  absl::StatusOr<std::vector<SweepRecord>> ListOpenSweeps();
  // NOT_FOUND for an unknown id.
  absl::StatusOr<SweepRecord> GetSweep(absl::string_view sweep_id);
  // Every sweep, oldest first.
  absl::StatusOr<std::vector<SweepRecord>> ListSweeps();
  // The sweep's runs, oldest first. NOT_FOUND for an unknown sweep.
  absl::StatusOr<std::vector<RunRecord>> ListSweepRuns(absl::string_view sweep_id);
  // Cancels every queued or running run of the sweep; a study sweep is closed and its running
  // study trials fail. NOT_FOUND; FAILED_PRECONDITION if none of its runs was queued or running
  // and it was not open.
  absl::StatusOr<SweepRecord> CancelSweep(absl::string_view sweep_id, absl::Time now);
  // Queues the sweep's failed runs again (each resumes from its last checkpoint, as a run whose
  // learner was lost does) and returns how many. NOT_FOUND; FAILED_PRECONDITION if none failed,
  // or for a study sweep (its study was told those trials failed).
  absl::StatusOr<std::pair<SweepRecord, int>> RetrySweep(absl::string_view sweep_id,
                                                         absl::Time now);

  // Studies (coordinator/study_store.cc): ask-and-tell, as Optuna's. Creates a study, or returns
  // the one `submission.request_id` already created. INVALID_ARGUMENT for an empty request id,
  // a space that does not parse or validate (naming the problem), or TPE or pruner options out of
  // range.
  absl::StatusOr<StudyRecord> CreateStudy(const StudySubmission& submission, absl::Time now);
  // NOT_FOUND for an unknown id.
  absl::StatusOr<StudyRecord> GetStudy(absl::string_view study_id);
  // Every study, oldest first.
  absl::StatusOr<std::vector<StudyRecord>> ListStudies();
  // A new running trial, numbered after the study's others, with the values its sampler gives
  // given every trial so far; or the trial `request_id` already asked for (a retry).
  // NOT_FOUND for an unknown study; INVALID_ARGUMENT for an empty request id.
  absl::StatusOr<StudyTrial> AskTrial(absl::string_view study_id, absl::string_view request_id,
                                      absl::Time now);
  // Finishes a running trial: complete with `value` (a NaN value fails it, as Optuna's tell
  // does; ±inf is a value), pruned (its value, if any, is its last report), or failed.
  // Telling a finished trial what it was told (a retry) returns it unchanged. NOT_FOUND for an
  // unknown study or trial; FAILED_PRECONDITION if the trial finished otherwise (naming its
  // state); INVALID_ARGUMENT for `state` running.
  absl::StatusOr<StudyTrial> TellTrial(absl::string_view study_id, int64_t number,
                                       TrialState state, double value, absl::Time now);
  // Records a running trial's intermediate value at `step` (a repeated step keeps the first,
  // as Optuna's report) and returns whether the study's pruner says to stop it (never with no
  // pruner; the caller then tells it pruned). NOT_FOUND; FAILED_PRECONDITION if the trial has
  // finished.
  absl::StatusOr<bool> ReportTrial(absl::string_view study_id, int64_t number, int64_t step,
                                   double value);
  // The study's trials, by number. NOT_FOUND for an unknown study.
  absl::StatusOr<std::vector<StudyTrial>> ListStudyTrials(absl::string_view study_id);

  // A queued run a learner with `numerics` may take, leased to `holder` (listening at
  // `address`) until now + lease_duration; the run becomes running. Fair across sweeps: the
  // run whose sweep has the fewest running runs (a run alone counts as a sweep of its own),
  // the oldest among those; so a small sweep submitted after a big one is not starved.
  // nullopt if there is none; FAILED_PRECONDITION, naming both fingerprints, if the only queued
  // runs compute with other numerics.
  absl::StatusOr<std::optional<LearnerLease>> AcquireRun(absl::string_view holder,
                                                         absl::string_view address,
                                                         absl::string_view numerics,
                                                         absl::Time now);

  // A free env slot of a running run (whose learner holds its lease) that an actor with
  // `numerics` may step, skipping the runs whose learner lease is, at the same epoch, among
  // `complete_learners` (learners that told the actor they have all their steps: their runs
  // need no slots while they evaluate; the run's next learner, after one dies, does). nullopt
  // if there is none; FAILED_PRECONDITION as AcquireRun when the runs waiting for actors
  // compute with others.
  absl::StatusOr<std::optional<SlotLease>> AcquireSlot(absl::string_view holder,
                                                       absl::string_view numerics,
                                                       absl::Span<const LeaseKey> complete_learners,
                                                       absl::Time now);

  // Extends a held lease to now + lease_duration. FAILED_PRECONDITION if the lease moved (its
  // epoch is newer), lapsed and went back to the queue, or its run ended (the message says
  // which); NOT_FOUND for an unknown run or slot.
  absl::Status RenewLease(const LeaseKey& key, absl::Time now);

  // The holder gives a lease back (it stops stepping the slot, say). Errors as RenewLease.
  absl::Status ReleaseLease(const LeaseKey& key, absl::Time now);

  // The learner holding `key` hands over an evaluation. Idempotent: the same policy version
  // again is accepted as it stands. INVALID_ARGUMENT for no contexts, episodes or weights, for
  // a negative policy version (those key grid evaluations), or for a version submitted before
  // with other contexts or episodes; otherwise errors as RenewLease.
  absl::Status SubmitEvaluation(const LeaseKey& key, const EvaluationRequest& evaluation,
                                absl::Time now);

  // A client hands over a grid evaluation of a run in any state, ended ones included: one job
  // per cell, whose results GetEvaluation gives under the returned key (a negative policy
  // version of the run, the next one free). Idempotent: a request id seen before returns the
  // key it was given, the request as it stands. INVALID_ARGUMENT for no request id, cells,
  // episodes, grid or weights, or a request id used before for another run; NOT_FOUND for an
  // unknown run. The policy is dropped once every cell is in; the results are kept.
  absl::StatusOr<int64_t> SubmitGridEvaluation(const GridEvaluationRequest& evaluation,
                                               absl::Time now);

  // Free jobs of the oldest evaluation with any that an actor with `numerics` may run (of a
  // running run; or, if `grid_cells`, the actor evaluates them, cells of a grid evaluation of
  // any run), leased to `holder` until now + lease_duration: at most `max_jobs`, and at most
  // this actor's share of them among `actors` actors (at least 1), rounded up, so that one
  // evaluation spreads over the cluster while each actor takes its part in one call. A run's
  // own evaluations go before grid evaluations, however old: a learner may be waiting for its
  // result, and they are a few jobs each; a grid waits for an actor at most as long as the
  // runs' evaluations keep every actor busy. nullopt if there is none.
  absl::StatusOr<std::optional<EvaluationGrant>> AcquireEvaluationJobs(absl::string_view holder,
                                                                       absl::string_view numerics,
                                                                       int max_jobs, int actors,
                                                                       bool grid_cells,
                                                                       absl::Time now);

  // The holder delivers jobs' results, all of them or (on an error) none; returns, for each,
  // whether it was delivered before (a retry). Any holder the job was granted to may deliver
  // it, also after its lease lapsed and the job went to another: its result is the same whoever
  // computes it, and the first delivery is kept. Errors name the job: NOT_FOUND for an unknown
  // one; FAILED_PRECONDITION for an epoch it was never granted at; INVALID_ARGUMENT for a
  // number of returns other than the evaluation's episodes or a non-finite one.
  absl::StatusOr<std::vector<bool>> ReportEvaluationJobs(absl::Span<const JobResult> results);

  // Where the evaluation of `policy_version` of `run_id` stands (a grid evaluation's: its
  // key; its contexts are the cells). NOT_FOUND if it was never submitted.
  absl::StatusOr<EvaluationProgress> GetEvaluation(absl::string_view run_id,
                                                   int64_t policy_version);

  // Frees every lease whose deadline passed; a run whose learner lease lapsed goes back to
  // queued (and its slot leases are freed); a lapsed evaluation job goes back to the queue.
  // Returns how many leases lapsed.
  absl::StatusOr<int> ExpireLeases(absl::Time now);
  // How many leases have lapsed since the store was opened, whichever call expired them
  // (ExpireLeases or an Acquire): counted once each, when the expiring transaction commits.
  int64_t LeasesLapsed();

  // The learner holding `key` (a learner lease) reports progress. Errors as RenewLease.
  absl::Status ReportProgress(const LeaseKey& key, const RunProgress& progress, absl::Time now);

  // Indexes a checkpoint the caller has stored durably. Errors as RenewLease.
  absl::Status RecordCheckpoint(const LeaseKey& key, const CheckpointRecord& checkpoint,
                                absl::Time now);
  // A run's checkpoints, oldest first.
  absl::StatusOr<std::vector<CheckpointRecord>> ListCheckpoints(absl::string_view run_id);

  // The learner holding `key` ends its run: completed, or failed with `error`; every lease of
  // the run is freed. Errors as RenewLease; INVALID_ARGUMENT for another state.
  absl::Status FinishRun(const LeaseKey& key, RunState state, absl::string_view error,
                         absl::Time now);

  absl::StatusOr<StoreCounts> Counts();

  // Writes a consistent copy of the store as of one moment (SQLite's online backup) to `path`,
  // atomically: into a temporary file beside it, synced, then renamed over it; a failed backup
  // leaves nothing behind. Open opens the copy as it would this store, and a coordinator on it
  // goes on as one restarted on this store would (given the runs' files, which are not in the
  // store: coordinator/run_files.h). The copy is taken in one step under the store's lock, so
  // every other call waits for it (bench/RESULTS.md, Reliability: how long). Returns what the
  // copy holds. Errors name `path`: PERMISSION_DENIED for a directory it may not write in,
  // NOT_FOUND for a missing one, RESOURCE_EXHAUSTED for a full disk, else INTERNAL.
  absl::StatusOr<BackupCounts> Backup(const std::string& path);

 private:
  RunStore(std::unique_ptr<SQLite::Database> db, RunStoreOptions options);

  // Runs `body` in one transaction (defined in coordinator/store_rows.h).
  template <typename Body>
  auto Transaction(Body body) -> decltype(body());
  // Frees the leases lapsed at `now` (store_rows' ExpireLapsed), counting them for
  // LeasesLapsed if the transaction commits. Inside Transaction only.
  absl::Status ExpireLapsedLeases(absl::Time now) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_);

  absl::Mutex mu_;
  const std::unique_ptr<SQLite::Database> db_ ABSL_GUARDED_BY(mu_);
  const RunStoreOptions options_;
  int64_t leases_lapsed_ ABSL_GUARDED_BY(mu_) = 0;
  int64_t leases_lapsing_ ABSL_GUARDED_BY(mu_) = 0;  // by the open transaction
};

}  // namespace dcs::coordinator

#endif  // DCS_COORDINATOR_RUN_STORE_H_
