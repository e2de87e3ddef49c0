// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_COORDINATOR_SERVICE_H_
#define DCS_SERVICES_COORDINATOR_COORDINATOR_SERVICE_H_

// dcs.v1.CoordinatorService over the coordinator library: each method decodes the request,
// calls the library, encodes the reply and converts the status. Every call comes in through
// ServedCalls (services/served_calls.h), which authenticates it; what touches the store or the
// runs' directories runs on the service's work pool, never on gRPC's threads; membership
// (memory only) is answered inline. Workers' membership is in coordinator_service.cc, runs,
// leases and the store's backups in coordinator_runs.cc, sweeps in coordinator_sweeps.cc,
// watches of runs and sweeps in coordinator_watch.cc. The calls by which workers ask for work
// (AcquireRun, AcquireSlot, AcquireEvaluation) and a learner for its evaluation (GetEvaluation)
// may wait for it: with a `wait`, a call that finds nothing is parked (services/parked_calls.h)
// until the work may have come (a run submitted, a run taken, an evaluation submitted, its last
// job reported) or its wait is up. A watch streams only what changed: each handler that changes
// a run or a sweep says so (Watchers::Notify), and the watch's stream looks at the store again
// (services/coordinator/watchers.h). Thread-safe.
// Borrows the registry and the store (must outlive the service); owns its metrics'
// registration.

#include <prometheus/counter.h>
#include <prometheus/gauge.h>
#include <prometheus/registry.h>

#include <functional>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "coordinator/study_sweep_driver.h"
#include "coordinator/sweep_results.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/evaluation.pb.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "run/run_checkpoint.h"
#include "services/build_info.h"
#include "services/coordinator/watchers.h"
#include "services/grpc_status.h"
#include "services/parked_calls.h"
#include "services/refusal_counter.h"
#include "services/served_calls.h"
#include "services/work_pool.h"

namespace dcs::services {

// Where the coordinator keeps runs.
struct RunStorage {
  coordinator::Store* store = nullptr;  // borrowed
  // Borrowed; it keeps each study sweep's spec as SubmitSweep read it. None: no one here steps
  // study sweeps (they wait in the store).
  coordinator::StudySweepDriver* study_sweeps = nullptr;
  std::string data_dir;                 // runs' directories: coordinator/run_files.h
  absl::Duration lease_duration = absl::Seconds(10);
  int keep_checkpoints = 3;
};

class CoordinatorService final : public v1::CoordinatorService::CallbackService {
 public:
  // Registers dcs_worker_registrations_total{role}, dcs_leases_granted_total{kind},
  // dcs_runs_failed_total, dcs_requests_rejected_total{reason} and dcs_watchers{kind} in
  // `metrics`, which must outlive the service.
  CoordinatorService(coordinator::WorkerRegistry& registry, RunStorage runs, BuildInfo build,
                     absl::Time start_time, prometheus::Registry& metrics);

  grpc::ServerUnaryReactor* RegisterWorker(grpc::CallbackServerContext* context,
                                           const v1::RegisterWorkerRequest* request,
                                           v1::RegisterWorkerResponse* response) override;
  grpc::ServerUnaryReactor* Heartbeat(grpc::CallbackServerContext* context,
                                      const v1::HeartbeatRequest* request,
                                      v1::HeartbeatResponse* response) override;
  grpc::ServerUnaryReactor* UnregisterWorker(grpc::CallbackServerContext* context,
                                             const v1::UnregisterWorkerRequest* request,
                                             v1::UnregisterWorkerResponse* response) override;
  grpc::ServerUnaryReactor* GetClusterStatus(grpc::CallbackServerContext* context,
                                             const v1::GetClusterStatusRequest* request,
                                             v1::GetClusterStatusResponse* response) override;


  grpc::ServerUnaryReactor* SubmitRun(grpc::CallbackServerContext* context,
                                      const v1::SubmitRunRequest* request,
                                      v1::SubmitRunResponse* response) override;
  grpc::ServerUnaryReactor* GetRun(grpc::CallbackServerContext* context,
                                   const v1::GetRunRequest* request,
                                   v1::GetRunResponse* response) override;
  grpc::ServerUnaryReactor* ListRuns(grpc::CallbackServerContext* context,
                                     const v1::ListRunsRequest* request,
                                     v1::ListRunsResponse* response) override;
  grpc::ServerUnaryReactor* CancelRun(grpc::CallbackServerContext* context,
                                      const v1::CancelRunRequest* request,
                                      v1::CancelRunResponse* response) override;
  // Ended runs removed for good, store first, then files (coordinator/run_removal.h).
  grpc::ServerUnaryReactor* DeleteRuns(grpc::CallbackServerContext* context,
                                       const v1::DeleteRunsRequest* request,
                                       v1::DeleteRunsResponse* response) override;
  grpc::ServerWriteReactor<v1::RunFile>* GetRunFiles(
      grpc::CallbackServerContext* context, const v1::GetRunFilesRequest* request) override;
  grpc::ServerWriteReactor<v1::BackupPiece>* BackupStore(
      grpc::CallbackServerContext* context, const v1::BackupStoreRequest* request) override;

  grpc::ServerUnaryReactor* SubmitSweep(grpc::CallbackServerContext* context,
                                        const v1::SubmitSweepRequest* request,
                                        v1::SubmitSweepResponse* response) override;
  grpc::ServerUnaryReactor* GetSweep(grpc::CallbackServerContext* context,
                                     const v1::GetSweepRequest* request,
                                     v1::GetSweepResponse* response) override;
  grpc::ServerUnaryReactor* ListSweeps(grpc::CallbackServerContext* context,
                                       const v1::ListSweepsRequest* request,
                                       v1::ListSweepsResponse* response) override;
  grpc::ServerUnaryReactor* CancelSweep(grpc::CallbackServerContext* context,
                                        const v1::CancelSweepRequest* request,
                                        v1::CancelSweepResponse* response) override;
  grpc::ServerUnaryReactor* RetrySweep(grpc::CallbackServerContext* context,
                                       const v1::RetrySweepRequest* request,
                                       v1::RetrySweepResponse* response) override;
  grpc::ServerUnaryReactor* DeleteSweeps(grpc::CallbackServerContext* context,
                                         const v1::DeleteSweepsRequest* request,
                                         v1::DeleteSweepsResponse* response) override;
  grpc::ServerUnaryReactor* GetSweepResults(grpc::CallbackServerContext* context,
                                            const v1::GetSweepResultsRequest* request,
                                            v1::SweepResults* response) override;
  grpc::ServerUnaryReactor* AcquireRun(grpc::CallbackServerContext* context,
                                       const v1::AcquireRunRequest* request,
                                       v1::AcquireRunResponse* response) override;
  grpc::ServerUnaryReactor* AcquireSlot(grpc::CallbackServerContext* context,
                                        const v1::AcquireSlotRequest* request,
                                        v1::AcquireSlotResponse* response) override;
  grpc::ServerUnaryReactor* RenewLease(grpc::CallbackServerContext* context,
                                       const v1::RenewLeaseRequest* request,
                                       v1::RenewLeaseResponse* response) override;
  grpc::ServerUnaryReactor* ReleaseLease(grpc::CallbackServerContext* context,
                                         const v1::ReleaseLeaseRequest* request,
                                         v1::ReleaseLeaseResponse* response) override;
  // Studies (services/coordinator_studies.cc).
  grpc::ServerUnaryReactor* CreateStudy(grpc::CallbackServerContext* context,
                                        const v1::CreateStudyRequest* request,
                                        v1::CreateStudyResponse* response) override;
  grpc::ServerUnaryReactor* GetStudy(grpc::CallbackServerContext* context,
                                     const v1::GetStudyRequest* request,
                                     v1::GetStudyResponse* response) override;
  grpc::ServerUnaryReactor* ListStudies(grpc::CallbackServerContext* context,
                                        const v1::ListStudiesRequest* request,
                                        v1::ListStudiesResponse* response) override;
  grpc::ServerUnaryReactor* AskTrial(grpc::CallbackServerContext* context,
                                     const v1::AskTrialRequest* request,
                                     v1::AskTrialResponse* response) override;
  grpc::ServerUnaryReactor* TellTrial(grpc::CallbackServerContext* context,
                                      const v1::TellTrialRequest* request,
                                      v1::TellTrialResponse* response) override;
  grpc::ServerUnaryReactor* ReportTrial(grpc::CallbackServerContext* context,
                                        const v1::ReportTrialRequest* request,
                                        v1::ReportTrialResponse* response) override;
  grpc::ServerUnaryReactor* ReportProgress(grpc::CallbackServerContext* context,
                                           const v1::ReportProgressRequest* request,
                                           v1::ReportProgressResponse* response) override;
  grpc::ServerReadReactor<v1::PutCheckpointRequest>* PutCheckpoint(
      grpc::CallbackServerContext* context, v1::PutCheckpointResponse* response) override;
  grpc::ServerWriteReactor<v1::CheckpointPiece>* GetCheckpoint(
      grpc::CallbackServerContext* context, const v1::GetCheckpointRequest* request) override;
  grpc::ServerUnaryReactor* FinishRun(grpc::CallbackServerContext* context,
                                      const v1::FinishRunRequest* request,
                                      v1::FinishRunResponse* response) override;
  grpc::ServerReadReactor<v1::SubmitEvaluationRequest>* SubmitEvaluation(
      grpc::CallbackServerContext* context, v1::SubmitEvaluationResponse* response) override;
  grpc::ServerReadReactor<v1::SubmitGridEvaluationRequest>* SubmitGridEvaluation(
      grpc::CallbackServerContext* context, v1::SubmitGridEvaluationResponse* response) override;
  grpc::ServerUnaryReactor* GetEvaluation(grpc::CallbackServerContext* context,
                                          const v1::GetEvaluationRequest* request,
                                          v1::GetEvaluationResponse* response) override;
  grpc::ServerWriteReactor<v1::AcquireEvaluationResponse>* AcquireEvaluation(
      grpc::CallbackServerContext* context, const v1::AcquireEvaluationRequest* request) override;
  grpc::ServerUnaryReactor* ReportEvaluation(grpc::CallbackServerContext* context,
                                             const v1::ReportEvaluationRequest* request,
                                             v1::ReportEvaluationResponse* response) override;
  // Watches (coordinator_watch.cc).
  grpc::ServerWriteReactor<v1::GetRunResponse>* WatchRun(
      grpc::CallbackServerContext* context, const v1::WatchRunRequest* request) override;
  grpc::ServerWriteReactor<v1::GetSweepResponse>* WatchSweep(
      grpc::CallbackServerContext* context, const v1::WatchSweepRequest* request) override;

  // Runs changed, and their writer cannot say which (the lease reaper returned lapsed leases'
  // runs to the queue, a study sweep stepped): every watch looks again, and every call parked
  // for work asks again.
  void RunsChanged();
  // Ends every watch with UNAVAILABLE (its client watches again once the coordinator is back),
  // and each begun later: the coordinator stops. Call before the server drains.
  void StopWatches();

 private:
  // What parked calls wait for (ParkedCalls topics), each woken by whatever makes it: a queued
  // run (AcquireRun: a run submitted or released), a free slot of a run its learner hosts
  // (AcquireSlot: a slot released, or the learner fetching the run's checkpoint, which it does
  // as it loads the run), an open evaluation job (AcquireEvaluation: an evaluation submitted),
  // and one evaluation's last result (GetEvaluation); any of the first three by RunsChanged (a
  // lease lapsed, a sweep retried, a study sweep's trials asked).
  static constexpr char kRunsTopic[] = "runs";
  static constexpr char kSlotsTopic[] = "slots";
  static constexpr char kEvaluationJobsTopic[] = "evaluation jobs";
  static std::string EvaluationTopic(absl::string_view run_id, int64_t policy_version);
  // What watches follow (Watchers topics): a run, a sweep. A handler that changed a run or a
  // sweep notifies its topic; a sweep's watch follows its runs' too.
  static std::string RunTopic(absl::string_view run_id);
  // A watch sends at most one message per interval, as often as `dcs` asked before it watched
  // (GetRun every 250 ms, GetSweep every second): a burst of changes (a sweep's runs all
  // reporting progress) reaches it as its latest state, and a watch costs the store no more
  // reads than a poll did, however busy its runs are.
  static constexpr absl::Duration kRunWatchInterval = absl::Milliseconds(250);
  static constexpr absl::Duration kSweepWatchInterval = absl::Seconds(1);
  static std::string SweepTopic(absl::string_view sweep_id);
  // What GetRun (GetSweep) answers, and each message of a watch of the run (the sweep): all the
  // store reads of one answer.
  absl::StatusOr<v1::GetRunResponse> ReadRun(const std::string& run_id) const;
  absl::StatusOr<v1::GetSweepResponse> ReadSweep(const std::string& sweep_id) const;

  // Makes a call's answer with `attempt`, which prepares it and returns whether it found what
  // the caller waits for, then gives it with `answer` (its status, counted if a refusal). With
  // a positive `wait`, until an attempt finds it, the call is parked under `topic` (tried
  // again at each Wake of it; calls of one `question` are tried until one finds nothing:
  // ParkedCalls) for that long at most (ParkingDeadline), then answered as its last attempt
  // left it (GetEvaluation's says how far the evaluation is; an Acquire's holds nothing).
  // `attempt` and `answer` run on the pool or the parked calls' thread, not the handler's: they
  // must hold what they read by value or by pointer to the call's own request and response.
  void AnswerOrPark(const grpc::CallbackServerContext& context,
                    const google::protobuf::Duration& wait, std::string topic,
                    std::string question, std::function<absl::StatusOr<bool>()> attempt,
                    std::function<void(const absl::Status&)> answer);
  // AnswerOrPark for a unary call: `attempt` fills its response, which goes with its status.
  grpc::ServerUnaryReactor* AnswerOrPark(grpc::CallbackServerContext* context,
                                         const google::protobuf::Duration& wait,
                                         std::string topic, std::string question,
                                         std::function<absl::StatusOr<bool>()> attempt);
  // After runs were removed (coordinator/run_removal.h): their kept logs are dropped. Their
  // watches need no word: a removed run ended, and so did its watch, or it will at the look its
  // end asked for, finding the run gone (NOT_FOUND).
  void RunsRemoved(const std::vector<coordinator::RunRecord>& runs);
  // Logs the error removing removed runs' directories, if any: the next start removes them.
  static void LogLeftDirectories(const absl::Status& files);
  // The actors heartbeating now, who share each evaluation's jobs.
  int AliveActors() const;
  // Stores a checkpoint a learner streamed (PutCheckpoint), with the evaluation log as of it
  // from evaluation `first_evaluation` on (coordinator::StoreCheckpoint).
  absl::Status StoreCheckpoint(const coordinator::LeaseKey& key,
                               const run::PackedCheckpoint& checkpoint, int64_t first_evaluation,
                               const v1::EvaluationLog& log_since);

  coordinator::WorkerRegistry& registry_;
  const RunStorage runs_;
  coordinator::CompletedRunLogs completed_logs_;  // what sweeps' reports read
  const v1::BuildInfo build_;
  const absl::Time start_time_;
  prometheus::Counter& learner_registrations_;
  prometheus::Counter& actor_registrations_;
  prometheus::Counter& learner_leases_;
  prometheus::Counter& slot_leases_;
  prometheus::Counter& evaluation_leases_;
  prometheus::Counter& runs_failed_;
  RefusalCounter rejected_;
  prometheus::Gauge& run_watchers_;
  prometheus::Gauge& sweep_watchers_;
  // Every watch is removed from it by its call's end, before the service goes; outlives the
  // pool, whose work notifies it.
  Watchers watchers_;
  // Destroyed after the pool, whose work may wake parked calls, answering the calls still
  // parked while the rest is alive.
  ParkedCalls parked_;
  // Destroyed first, running the work queued while the rest is alive. The store is one
  // connection behind a mutex, so more threads would only wait for it; these let a read wait
  // for a commit while another call's files are written. A full queue refuses
  // (RESOURCE_EXHAUSTED): 1024 calls wait already, seconds of work.
  WorkPool pool_{{.threads = 4, .max_queued = 1024}};
  ServedCalls calls_{pool_, &rejected_};
};

// When a call parked with `wait` is answered at the latest: `wait` from now (at most 10 s), and
// early enough before its own deadline for the answer to reach the caller.
absl::Time ParkingDeadline(const grpc::CallbackServerContext& context, absl::Duration wait);

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_COORDINATOR_SERVICE_H_
