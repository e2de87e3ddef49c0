// Copyright 2026 The DCS Authors.
//
// A fleet of thousands, simulated (issue 35, item 12): how large a cluster one coordinator
// holds. One process plays `--actors` actors and `--learners` learners against a real
// dcs-coordinator over gRPC, each with a channel (a connection) of its own, making the calls
// the real workers make, at their cadence, without training:
//   every worker (services/worker_agent.cc): RegisterWorker, then Heartbeat at the interval
//     the coordinator answers;
//   an actor's slots (services/actor/slot_workers.cc): a round every poll interval renews the
//     leases that fall due (a third of a lease after the last renewal) and, with room for a
//     slot, asks for one (AcquireSlot, held at the coordinator up to the poll interval); a
//     slot is released when its run's learner says the run is complete (here: the simulated
//     learner, in this process);
//   an actor's evaluations (services/actor/evaluation_worker.cc): AcquireEvaluation, held up to
//     the poll interval; the jobs granted take --job-seconds each; ReportEvaluation with every
//     episode's return; as many jobs next time as fit in half a lease;
//   a learner (services/learner/hosted_runs.cc, remote_evaluation.cc): AcquireRun, held up to
//     the poll interval, while it hosts fewer than --runs-per-learner; GetCheckpoint as it
//     loads a run; renewals as an actor's; per run, ReportProgress after each update (n_steps x
//     n_envs steps of the run's config, its slots stepping --slot-steps-per-second each);
//     at every eval_freq steps and at the end SubmitEvaluation (a policy of the real
//     CartPole network's size), GetEvaluation until every context is in (held half a poll
//     interval), then PutCheckpoint (a checkpoint of a real one's size); FinishRun at the end.
// The intervals are the real workers' defaults (their options structs, the coordinator's
// answers); the sweep's runs are CartPole runs of --sweep-spec.
//
// After --warmup it measures for --seconds: every call's latency per method (from the
// simulator's side, so including its own queueing; p50, p99), the calls answered per second,
// the coordinator's CPU (cores, from /proc/<pid>/stat), its RSS at the end of the window and
// its peak (VmHWM), and this process's CPU. Prints one row of the table bench/cluster/fleet.sh
// assembles, then every method's figures. A long poll's latency is its wait when nothing came;
// "overrun" is how far past its wait it was answered.
//
// Usage: fleet_benchmark --coordinator 127.0.0.1:PORT --pid PID --sweep-spec sweep.yaml
//          --actors 2000 --learners 200 [--warmup 20s --seconds 60s ...]

#include <grpcpp/grpcpp.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <queue>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/container/flat_hash_set.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "dcs/v1/trajectory.pb.h"
#include "run/lease_key.h"
#include "run/run_checkpoint.h"
#include "run/run_spec_yaml.h"
#include "services/actor/evaluation_worker.h"
#include "services/actor/slot_workers.h"
#include "services/pieces.h"
#include "services/run_proto.h"
#include "services/time_proto.h"

namespace dcs::bench {
namespace {

using services::DurationFromProto;
using v1::CoordinatorService;

// What the learner's defaults are (services/learner/hosted_runs.h HostedRunsOptions: a poll
// interval of 200 ms, half of it for an evaluation's results; 10 s per call). Not included:
// that header brings the learner's, and libtorch's, build along.
constexpr absl::Duration kLearnerPollInterval = absl::Milliseconds(200);
constexpr absl::Duration kLearnerRpcTimeout = absl::Seconds(10);
// A CartPole policy as actors get it (4 inputs, 64 x 64, 2 actions) and the size of a CartPole
// run's checkpoint (learner.bin: both networks' weights and Adam's two moments).
constexpr int kPolicyFloats = 4 * 64 + 64 + 64 * 64 + 64 + 64 * 2 + 2;
constexpr int kLearnerBinBytes = 4 * 3 * (kPolicyFloats + 4 * 64 + 64 + 64 * 64 + 64 + 65);

// Tasks at times, run one at a time on the loop's thread: every simulated worker's logic runs
// on one loop, so it needs no lock. Thread-safe.
class EventLoop {
 public:
  EventLoop() : thread_([this] { Run(); }) {}
  ~EventLoop() {
    {
      absl::MutexLock lock(&mu_);
      stopping_ = true;
    }
    thread_.join();
  }

  void At(absl::Time when, std::function<void()> task) {
    absl::MutexLock lock(&mu_);
    tasks_.push({when, next_++, std::move(task)});
  }
  void Now(std::function<void()> task) { At(absl::Now(), std::move(task)); }

 private:
  struct Task {
    absl::Time when;
    uint64_t order;
    std::function<void()> run;
    bool operator>(const Task& other) const {
      return std::tie(when, order) > std::tie(other.when, other.order);
    }
  };

  void Run() {
    absl::MutexLock lock(&mu_);
    while (!stopping_) {
      if (tasks_.empty() || tasks_.top().when > absl::Now()) {
        const absl::Time until = tasks_.empty() ? absl::Now() + absl::Milliseconds(50)
                                                : tasks_.top().when;
        auto woken = [this]() ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
          return stopping_ || (!tasks_.empty() && tasks_.top().when <= absl::Now());
        };
        mu_.AwaitWithDeadline(absl::Condition(&woken), until);
        continue;
      }
      std::function<void()> task = std::move(const_cast<Task&>(tasks_.top()).run);
      tasks_.pop();
      mu_.Unlock();
      task();
      mu_.Lock();
    }
  }

  absl::Mutex mu_;
  std::priority_queue<Task, std::vector<Task>, std::greater<>> tasks_ ABSL_GUARDED_BY(mu_);
  uint64_t next_ ABSL_GUARDED_BY(mu_) = 0;
  bool stopping_ ABSL_GUARDED_BY(mu_) = false;
  std::thread thread_;
};

// Latencies per method while recording. Thread-safe.
class Latencies {
 public:
  struct Figures {
    int64_t calls = 0;
    int64_t failed = 0;
    std::map<std::string, int64_t> codes;  // of the failed
    std::vector<double> ms;
    std::vector<double> overrun_ms;  // long polls answered empty: past their wait
  };

  void Record(const std::string& method, absl::Duration latency, const grpc::Status& status,
              std::optional<absl::Duration> empty_wait = std::nullopt) {
    if (!recording_) return;
    absl::MutexLock lock(&mu_);
    Figures& figures = methods_[method];
    ++figures.calls;
    if (!status.ok()) {
      ++figures.failed;
      ++figures.codes[std::to_string(status.error_code())];
      return;
    }
    figures.ms.push_back(absl::ToDoubleMilliseconds(latency));
    if (empty_wait.has_value()) {
      figures.overrun_ms.push_back(
          std::max(0.0, absl::ToDoubleMilliseconds(latency - *empty_wait)));
    }
  }

  void Start() { recording_ = true; }
  std::map<std::string, Figures> Stop() {
    recording_ = false;
    absl::MutexLock lock(&mu_);
    return std::move(methods_);
  }

 private:
  std::atomic<bool> recording_{false};
  absl::Mutex mu_;
  std::map<std::string, Figures> methods_ ABSL_GUARDED_BY(mu_);
};

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return NAN;
  const size_t rank = std::min(values.size() - 1, static_cast<size_t>(q * values.size()));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[rank];
}

struct Options {
  std::string coordinator;
  int coordinator_pid = 0;
  std::string sweep_spec;
  int actors = 100;
  int learners = 10;
  int runs_per_learner = 2;
  double slot_steps_per_second = 1400;
  double job_seconds = 0.05;
  double warmup_s = 20;
  double seconds = 60;
  double ramp_s = 5;  // workers start spread over it, as a fleet's processes do
  int threads = 2;
};

// What every simulated worker shares. Thread-safe.
struct Fleet {
  Options options;
  Latencies latencies;
  std::vector<std::unique_ptr<EventLoop>> loops;
  std::atomic<bool> stopping{false};
  std::atomic<int64_t> in_flight{0};
  std::string policy;      // a serialised PolicyWeights
  std::string learner_bin;  // a checkpoint's learner.bin

  // Learner leases (run/epoch) whose runs the simulated learner finished: what a real learner
  // tells its slots' actors (GetSlotWork's run_complete).
  absl::Mutex complete_mu;
  absl::flat_hash_set<std::string> complete ABSL_GUARDED_BY(complete_mu);
};

std::string LeaseName(const run::LeaseKey& key) {
  return absl::StrCat(key.run_id, "/", key.slot, "@", key.epoch);
}

std::shared_ptr<grpc::Channel> WorkerChannel(const std::string& address) {
  grpc::ChannelArguments args;  // as services/channel.cc's, each worker its own connection
  args.SetInt(GRPC_ARG_KEEPALIVE_TIME_MS, 30'000);
  args.SetInt(GRPC_ARG_KEEPALIVE_TIMEOUT_MS, 10'000);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2'000);
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  return grpc::CreateCustomChannel(address, grpc::InsecureChannelCredentials(), args);
}

// A simulated worker: its stub, its loop, its calls. Confined to its loop's thread but for the
// calls' completions, which post back to it.
class Worker {
 public:
  Worker(Fleet& fleet, int index, std::string name)
      : fleet_(fleet),
        loop_(*fleet.loops[index % fleet.loops.size()]),
        name_(std::move(name)),
        stub_(CoordinatorService::NewStub(WorkerChannel(fleet.options.coordinator))) {}
  virtual ~Worker() = default;

  virtual void Start() = 0;

 protected:
  // A unary call: `start` issues it on the stub's async interface; `done` runs on the loop.
  template <typename Request, typename Response>
  using UnaryMethod = void (CoordinatorService::Stub::async::*)(
      grpc::ClientContext*, const Request*, Response*, std::function<void(grpc::Status)>);
  template <typename Request, typename Response>
  using UploadMethod = void (CoordinatorService::Stub::async::*)(
      grpc::ClientContext*, Response*, grpc::ClientWriteReactor<Request>*);
  template <typename Request, typename Response>
  using DownloadMethod = void (CoordinatorService::Stub::async::*)(
      grpc::ClientContext*, const Request*, grpc::ClientReadReactor<Response>*);

  template <typename Request, typename Response, typename Done>
  void Unary(const std::string& method, absl::Duration timeout, Request request,
             UnaryMethod<Request, Response> start, Done done,
             std::optional<absl::Duration> wait = std::nullopt) {
    struct Call {
      grpc::ClientContext context;
      Request request;
      Response response;
      absl::Time sent;
    };
    auto call = std::make_shared<Call>();
    call->request = std::move(request);
    call->context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
    call->sent = absl::Now();
    ++fleet_.in_flight;
    (stub_->async()->*start)(&call->context, &call->request, &call->response,
          [this, method, call, done = std::move(done), wait](grpc::Status status) mutable {
            const absl::Duration latency = absl::Now() - call->sent;
            const bool empty = wait.has_value() && status.ok() && !HasWork(call->response);
            fleet_.latencies.Record(method, latency, status,
                                    empty ? wait : std::optional<absl::Duration>());
            loop_.Now([this, call, status = std::move(status), done = std::move(done)] {
              --fleet_.in_flight;
              if (!fleet_.stopping) done(status, call->response);
            });
          });
  }

  // A client stream of `messages`, then its response.
  template <typename Request, typename Response, typename Done>
  void Upload(const std::string& method, std::vector<Request> messages,
              UploadMethod<Request, Response> start, Done done) {
    class Writer final : public grpc::ClientWriteReactor<Request> {
     public:
      Writer(Worker& worker, std::string method, std::vector<Request> messages, Done done)
          : worker_(worker), method_(std::move(method)), messages_(std::move(messages)),
            done_(std::move(done)) {}
      void Go() {
        sent_ = absl::Now();
        this->StartCall();
        WriteNext();
      }
      void OnWriteDone(bool ok) override {
        if (ok) WriteNext();
      }
      void OnDone(const grpc::Status& status) override {
        worker_.fleet_.latencies.Record(method_, absl::Now() - sent_, status);
        worker_.loop_.Now([worker = &worker_, status, done = std::move(done_)] {
          --worker->fleet_.in_flight;
          if (!worker->fleet_.stopping) done(status);
        });
        delete this;
      }
      grpc::ClientContext context;
      Response response;

     private:
      void WriteNext() {
        if (next_ == messages_.size()) {
          this->StartWritesDone();
          return;
        }
        this->StartWrite(&messages_[next_++]);
      }
      Worker& worker_;
      const std::string method_;
      std::vector<Request> messages_;
      size_t next_ = 0;
      Done done_;
      absl::Time sent_;
    };
    auto* writer = new Writer(*this, method, std::move(messages), std::move(done));
    writer->context.set_deadline(absl::ToChronoTime(absl::Now() + absl::Minutes(2)));
    ++fleet_.in_flight;
    (stub_->async()->*start)(&writer->context, &writer->response, writer);
    writer->Go();
  }

  // A server stream: every message read, then `done` with the first (or none) on the loop.
  template <typename Request, typename Response, typename Done>
  void Download(const std::string& method, absl::Duration timeout, Request request,
                DownloadMethod<Request, Response> start, Done done,
                std::optional<absl::Duration> wait = std::nullopt) {
    class Reader final : public grpc::ClientReadReactor<Response> {
     public:
      Reader(Worker& worker, std::string method, Request message, Done done,
             std::optional<absl::Duration> wait)
          : request(std::move(message)), worker_(worker), method_(std::move(method)),
            done_(std::move(done)), wait_(wait) {}
      void Go() {
        sent_ = absl::Now();
        this->StartRead(&message_);
        this->StartCall();
      }
      void OnReadDone(bool ok) override {
        if (!ok) return;
        if (!first_.has_value()) first_ = message_;
        this->StartRead(&message_);
      }
      void OnDone(const grpc::Status& status) override {
        const bool empty = wait_.has_value() && status.ok() &&
                           (!first_.has_value() || !HasWork(*first_));
        // GetCheckpoint's NOT_FOUND says the run has none yet: an answer, not a refusal.
        const bool answered = status.error_code() == grpc::StatusCode::NOT_FOUND &&
                              std::is_same_v<Response, v1::CheckpointPiece>;
        worker_.fleet_.latencies.Record(method_, absl::Now() - sent_,
                                        answered ? grpc::Status::OK : status,
                                        empty ? wait_ : std::optional<absl::Duration>());
        worker_.loop_.Now([worker = &worker_, status, first = std::move(first_),
                           done = std::move(done_)] {
          --worker->fleet_.in_flight;
          if (!worker->fleet_.stopping) done(status, first);
        });
        delete this;
      }
      grpc::ClientContext context;
      Request request;

     private:
      Worker& worker_;
      const std::string method_;
      Done done_;
      std::optional<absl::Duration> wait_;
      Response message_;
      std::optional<Response> first_;
      absl::Time sent_;
    };
    auto* reader = new Reader(*this, method, std::move(request), std::move(done), wait);
    reader->context.set_deadline(absl::ToChronoTime(absl::Now() + timeout));
    ++fleet_.in_flight;
    (stub_->async()->*start)(&reader->context, &reader->request, reader);
    reader->Go();
  }

  // Whether a long poll's answer holds what it waited for.
  static bool HasWork(const v1::AcquireSlotResponse& response) { return response.has_lease(); }
  static bool HasWork(const v1::AcquireRunResponse& response) { return response.has_lease(); }
  static bool HasWork(const v1::AcquireEvaluationResponse& response) {
    return !response.jobs().empty();
  }
  static bool HasWork(const v1::GetEvaluationResponse& response) {
    return response.done() == response.contexts();
  }
  template <typename Response>
  static bool HasWork(const Response&) {
    return true;
  }

  // Membership (services/worker_agent.cc): register, then heartbeat at the interval answered.
  void Join(v1::WorkerRole role) {
    v1::RegisterWorkerRequest request;
    request.mutable_worker()->set_role(role);
    request.mutable_worker()->set_address(name_);
    Unary<v1::RegisterWorkerRequest, v1::RegisterWorkerResponse>(
        "RegisterWorker", absl::Seconds(2), request,
        &CoordinatorService::Stub::async::RegisterWorker,
        [this, role](const grpc::Status& status, const v1::RegisterWorkerResponse& response) {
          if (!status.ok()) {
            loop_.At(absl::Now() + absl::Seconds(1), [this, role] { Join(role); });
            return;
          }
          worker_id_ = response.worker_id();
          heartbeat_interval_ = DurationFromProto(response.heartbeat_interval());
          loop_.At(absl::Now() + heartbeat_interval_, [this, role] { Heartbeat(role); });
        });
  }

  void Heartbeat(v1::WorkerRole role) {
    v1::HeartbeatRequest request;
    request.set_worker_id(worker_id_);
    Unary<v1::HeartbeatRequest, v1::HeartbeatResponse>(
        "Heartbeat", absl::Seconds(2), request,
        &CoordinatorService::Stub::async::Heartbeat,
        [this, role](const grpc::Status& status, const v1::HeartbeatResponse&) {
          if (status.error_code() == grpc::StatusCode::NOT_FOUND) return Join(role);
          loop_.At(absl::Now() + heartbeat_interval_, [this, role] { Heartbeat(role); });
        });
  }

  // Renews the leases of `held` that fall due (services/lease_renewals.h RenewDueLeases): a
  // third of a lease after their last renewal; `lost` for one the coordinator refuses.
  struct Held {
    run::LeaseKey key;
    absl::Time renewed_at;
    bool renewing = false;
  };
  template <typename Lost>
  void RenewDue(std::map<std::string, Held>& held, Lost lost) {
    for (auto& [name, lease] : held) {
      if (lease.renewing || absl::Now() - lease.renewed_at < lease_duration_ / 3) continue;
      lease.renewing = true;
      v1::RenewLeaseRequest request;
      *request.mutable_lease() = services::LeaseToProto(lease.key);
      const absl::Time sent = absl::Now();
      Unary<v1::RenewLeaseRequest, v1::RenewLeaseResponse>(
          "RenewLease", absl::Seconds(10), request,
          &CoordinatorService::Stub::async::RenewLease,
          [this, &held, name, sent, lost](const grpc::Status& status,
                                          const v1::RenewLeaseResponse& response) {
            auto found = held.find(name);
            if (found == held.end()) return;
            found->second.renewing = false;
            if (status.ok()) {
              found->second.renewed_at = sent;
              lease_duration_ = DurationFromProto(response.lease_duration());
            } else if (status.error_code() == grpc::StatusCode::FAILED_PRECONDITION ||
                       status.error_code() == grpc::StatusCode::NOT_FOUND) {
              lost(name);
            }
          });
    }
  }

  Fleet& fleet_;
  EventLoop& loop_;
  const std::string name_;
  const std::unique_ptr<CoordinatorService::Stub> stub_;
  std::string worker_id_;
  absl::Duration heartbeat_interval_ = absl::Seconds(1);
  absl::Duration lease_duration_ = absl::Seconds(10);
};

// An actor: its slot manager and its evaluation worker (services/actor/).
class Actor final : public Worker {
 public:
  using Worker::Worker;

  void Start() override {
    loop_.Now([this] {
      Join(v1::WORKER_ROLE_ACTOR);
      SlotRound();
      AskForJobs();
    });
  }

 private:
  // SlotWorkers::Manage: renew, take a slot if there is room, wait out the round.
  void SlotRound() {
    const absl::Time round = absl::Now();
    ReleaseCompleteSlots();
    RenewDue(slots_, [this](const std::string& name) {
      slots_.erase(name);
      learner_of_.erase(name);
    });
    auto next = [this, round] {
      loop_.At(std::max(absl::Now(), round + slot_options_.poll_interval),
               [this] { SlotRound(); });
    };
    if (static_cast<int>(slots_.size()) >= slot_options_.max_slots) return next();
    v1::AcquireSlotRequest request;
    request.set_holder(name_);
    request.set_numerics("simulated");
    *request.mutable_wait() = services::DurationToProto(slot_options_.poll_interval);
    for (const auto& [name, until] : complete_learners_) {
      if (until > absl::Now()) *request.add_complete_learners() = services::LeaseToProto(
          complete_keys_.at(name));
    }
    Unary<v1::AcquireSlotRequest, v1::AcquireSlotResponse>(
        "AcquireSlot", slot_options_.rpc_timeout, request,
        &CoordinatorService::Stub::async::AcquireSlot,
        [this, next](const grpc::Status& status, const v1::AcquireSlotResponse& response) {
          if (status.ok() && response.has_lease()) {
            absl::StatusOr<run::LeaseKey> key = services::LeaseFromProto(response.lease());
            if (key.ok()) {
              slots_[LeaseName(*key)] = {.key = *key, .renewed_at = absl::Now()};
              learner_of_[LeaseName(*key)] = {.run_id = key->run_id,
                                              .slot = run::kLearnerSlot,
                                              .epoch = response.learner_epoch()};
              lease_duration_ = DurationFromProto(response.lease_duration());
            }
          }
          next();
        },
        slot_options_.poll_interval);
  }

  // A slot whose learner said its run is complete is released (SlotWorkers::Work), and the
  // learner's lease remembered so that AcquireSlot skips its run.
  void ReleaseCompleteSlots() {
    std::vector<std::string> complete;
    {
      absl::MutexLock lock(&fleet_.complete_mu);
      for (const auto& [name, held] : slots_) {
        if (fleet_.complete.contains(LeaseName(learner_of_.at(name)))) complete.push_back(name);
      }
    }
    for (const std::string& name : complete) {
      const run::LeaseKey learner = learner_of_.at(name);
      complete_learners_[LeaseName(learner)] = absl::Now() + 60 * lease_duration_;
      complete_keys_[LeaseName(learner)] = learner;
      v1::ReleaseLeaseRequest request;
      *request.mutable_lease() = services::LeaseToProto(slots_.at(name).key);
      request.set_run_complete(true);
      slots_.erase(name);
      learner_of_.erase(name);
      Unary<v1::ReleaseLeaseRequest, v1::ReleaseLeaseResponse>(
          "ReleaseLease", slot_options_.rpc_timeout, request,
          &CoordinatorService::Stub::async::ReleaseLease,
          [](const grpc::Status&, const v1::ReleaseLeaseResponse&) {});
    }
    std::erase_if(complete_learners_, [this](const auto& entry) {
      if (entry.second > absl::Now()) return false;
      complete_keys_.erase(entry.first);
      return true;
    });
  }

  // EvaluationWorker::Work and RunJobs.
  void AskForJobs() {
    const absl::Time asked = absl::Now();
    v1::AcquireEvaluationRequest request;
    request.set_holder(name_);
    request.set_numerics("simulated");
    request.set_max_jobs(jobs_wanted_);
    request.set_grid_cells(true);
    *request.mutable_wait() = services::DurationToProto(evaluation_options_.poll_interval);
    Download<v1::AcquireEvaluationRequest, v1::AcquireEvaluationResponse>(
        "AcquireEvaluation", evaluation_options_.rpc_timeout, request,
        &CoordinatorService::Stub::async::AcquireEvaluation,
        [this, asked](const grpc::Status& status,
                      const std::optional<v1::AcquireEvaluationResponse>& grant) {
          if (!status.ok() || !grant.has_value() || grant->jobs().empty()) {
            loop_.At(std::max(absl::Now(), asked + evaluation_options_.poll_interval),
                     [this] { AskForJobs(); });
            return;
          }
          const absl::Duration per_job = absl::Seconds(fleet_.options.job_seconds);
          const absl::Duration lease = DurationFromProto(grant->lease_duration());
          jobs_wanted_ = static_cast<int>(
              std::clamp(absl::FDivDuration(lease / 2, per_job), 1.0,
                         static_cast<double>(evaluation_options_.max_jobs)));
          v1::ReportEvaluationRequest report;
          for (const v1::EvaluationJob& job : grant->jobs()) {
            v1::JobResult& result = *report.add_results();
            *result.mutable_job() = job;
            for (int i = 0; i < grant->episodes(); ++i) result.mutable_result()->add_returns(500);
            result.mutable_result()->set_seconds(fleet_.options.job_seconds);
          }
          loop_.At(absl::Now() + per_job * grant->jobs_size(),
                   [this, report = std::move(report)] { Report(report); });
        });
  }

  void Report(const v1::ReportEvaluationRequest& report) {
    Unary<v1::ReportEvaluationRequest, v1::ReportEvaluationResponse>(
        "ReportEvaluation", evaluation_options_.rpc_timeout, report,
        &CoordinatorService::Stub::async::ReportEvaluation,
        [this](const grpc::Status&, const v1::ReportEvaluationResponse&) { AskForJobs(); });
  }

  const services::SlotWorkersOptions slot_options_{};
  const services::EvaluationWorkerOptions evaluation_options_{};
  std::map<std::string, Held> slots_;
  std::map<std::string, run::LeaseKey> learner_of_;  // by slot lease
  std::map<std::string, absl::Time> complete_learners_;      // until when
  std::map<std::string, run::LeaseKey> complete_keys_;
  int jobs_wanted_ = 1;
};

// A learner: its hosted runs (services/learner/hosted_runs.cc), each trained by the clock.
class Learner final : public Worker {
 public:
  using Worker::Worker;

  void Start() override {
    loop_.Now([this] {
      Join(v1::WORKER_ROLE_LEARNER);
      Round();
    });
  }

 private:
  struct Run {
    run::LeaseKey key;
    int64_t n_steps_per_update = 0;  // n_steps x n_envs
    int64_t eval_freq = 0;
    int64_t total_timesteps = 0;
    int contexts = 0;
    int episodes = 0;
    absl::Duration update;  // the time an update's rollout takes its slots
    int64_t timesteps = 0;
    int64_t updates = 0;
    int64_t next_evaluation = 0;
    bool evaluating = false;  // an evaluation (and its checkpoint) outstanding
  };

  // HostedRuns::Manage: renew, take a run while there is room (the next at once), else wait.
  void Round() {
    const absl::Time round = absl::Now();
    RenewDue(leases_, [this](const std::string& name) {
      leases_.erase(name);
      runs_.erase(name);
    });
    auto next = [this, round](bool took) {
      loop_.At(took ? absl::Now() : std::max(absl::Now(), round + kLearnerPollInterval),
               [this] { Round(); });
    };
    if (static_cast<int>(runs_.size()) >= fleet_.options.runs_per_learner) return next(false);
    v1::AcquireRunRequest request;
    request.set_holder(name_);
    request.set_address(name_);
    request.set_numerics("simulated");
    *request.mutable_wait() = services::DurationToProto(kLearnerPollInterval);
    Unary<v1::AcquireRunRequest, v1::AcquireRunResponse>(
        "AcquireRun", kLearnerRpcTimeout, request,
        &CoordinatorService::Stub::async::AcquireRun,
        [this, next](const grpc::Status& status, const v1::AcquireRunResponse& response) {
          if (!status.ok() || !response.has_lease()) return next(false);
          Host(response);
          next(true);
        },
        kLearnerPollInterval);
  }

  void Host(const v1::AcquireRunResponse& response) {
    absl::StatusOr<run::LeaseKey> key = services::LeaseFromProto(response.lease());
    absl::StatusOr<run::RunSpec> spec = run::ParseRunSpecYaml(response.config(), "run.yaml");
    if (!key.ok() || !spec.ok()) return;
    lease_duration_ = DurationFromProto(response.lease_duration());
    const std::string name = LeaseName(*key);
    Run& run = runs_[name];
    run.key = *key;
    run.n_steps_per_update = static_cast<int64_t>(spec->ppo.n_steps) * spec->n_envs;
    run.eval_freq = spec->eval_freq;
    run.next_evaluation = spec->eval_freq;
    run.total_timesteps = spec->total_timesteps;
    run.episodes = spec->eval_episodes;
    for (const std::vector<double>& values : spec->eval_contexts) {
      run.contexts += static_cast<int>(values.size());
    }
    run.update = absl::Seconds(spec->ppo.n_steps / fleet_.options.slot_steps_per_second);
    leases_[name] = {.key = *key, .renewed_at = absl::Now()};
    // HostedRuns::Load asks for the run's latest checkpoint (none yet: NOT_FOUND).
    v1::GetCheckpointRequest request;
    *request.mutable_lease() = services::LeaseToProto(*key);
    Download<v1::GetCheckpointRequest, v1::CheckpointPiece>(
        "GetCheckpoint", kLearnerRpcTimeout, request,
        &CoordinatorService::Stub::async::GetCheckpoint,
        [this, name](const grpc::Status&, const std::optional<v1::CheckpointPiece>&) {
          Train(name);
        });
  }

  // One update by the clock, then what HostedRuns::Train does after it.
  void Train(const std::string& name) {
    auto found = runs_.find(name);
    if (found == runs_.end()) return;  // lost
    loop_.At(absl::Now() + found->second.update, [this, name] {
      auto hosted = runs_.find(name);
      if (hosted == runs_.end()) return;
      Run& run = hosted->second;
      if (run.timesteps >= run.total_timesteps) {
        if (!run.evaluating) Finish(name);
        else Train(name);  // RunHost waits for the last evaluation
        return;
      }
      run.timesteps += run.n_steps_per_update;
      if (run.timesteps >= run.total_timesteps) {
        // The learner tells its actors the run has all its steps (GetSlotWork's run_complete).
        absl::MutexLock lock(&fleet_.complete_mu);
        fleet_.complete.insert(name);
      }
      ++run.updates;
      ReportProgress(run);
      if (run.timesteps >= run.next_evaluation || run.timesteps >= run.total_timesteps) {
        run.next_evaluation += run.eval_freq;
        if (!run.evaluating) Evaluate(name);
      }
      Train(name);
    });
  }

  void ReportProgress(const Run& run) {
    v1::ReportProgressRequest request;
    *request.mutable_lease() = services::LeaseToProto(run.key);
    *request.mutable_progress() = services::ProgressToProto(
        {.timesteps = run.timesteps, .policy_version = run.updates, .steps_per_second = 1,
         .recent_return = 100},
        run.total_timesteps);
    Unary<v1::ReportProgressRequest, v1::ReportProgressResponse>(
        "ReportProgress", kLearnerRpcTimeout, request,
        &CoordinatorService::Stub::async::ReportProgress,
        [](const grpc::Status&, const v1::ReportProgressResponse&) {});
  }

  // services/learner/remote_evaluation.cc: hand the policy over, ask until it is done; then
  // the checkpoint that fell due with it (learner/run_host.h).
  void Evaluate(const std::string& name) {
    Run& run = runs_.at(name);
    run.evaluating = true;
    v1::SubmitEvaluationRequest header;
    *header.mutable_lease() = services::LeaseToProto(run.key);
    header.set_policy_version(run.updates);
    header.set_step(run.timesteps);
    header.set_contexts(run.contexts);
    header.set_episodes(run.episodes);
    const int64_t version = run.updates;
    Upload<v1::SubmitEvaluationRequest, v1::SubmitEvaluationResponse>(
        "SubmitEvaluation",
        services::CutIntoMessages(std::move(header), fleet_.policy,
                                  &v1::SubmitEvaluationRequest::mutable_weights),
        &CoordinatorService::Stub::async::SubmitEvaluation,
        [this, name, version](const grpc::Status& status) {
          if (!status.ok()) return Evaluated(name);
          AwaitEvaluation(name, version);
        });
  }

  void AwaitEvaluation(const std::string& name, int64_t version) {
    auto found = runs_.find(name);
    if (found == runs_.end()) return;
    const absl::Duration poll = kLearnerPollInterval / 2;
    const absl::Time asked = absl::Now();
    v1::GetEvaluationRequest request;
    request.set_run_id(found->second.key.run_id);
    request.set_policy_version(version);
    *request.mutable_wait() = services::DurationToProto(poll);
    Unary<v1::GetEvaluationRequest, v1::GetEvaluationResponse>(
        "GetEvaluation", kLearnerRpcTimeout, request,
        &CoordinatorService::Stub::async::GetEvaluation,
        [this, name, version, asked, poll](const grpc::Status& status,
                                           const v1::GetEvaluationResponse& response) {
          if (status.ok() && response.done() == response.contexts()) return PutCheckpoint(name);
          loop_.At(std::max(absl::Now(), asked + poll),
                   [this, name, version] { AwaitEvaluation(name, version); });
        },
        poll);
  }

  void PutCheckpoint(const std::string& name) {
    auto found = runs_.find(name);
    if (found == runs_.end()) return;
    const Run& run = found->second;
    run::PackedCheckpoint checkpoint{.name = run::CheckpointName(run.timesteps),
                                     .learner = fleet_.learner_bin,
                                     .run_state = run::EncodeRunState({.timesteps = run.timesteps,
                                                                       .rollouts = run.updates})};
    checkpoint.learner_sha256 = run::Sha256Hex(checkpoint.learner);
    checkpoint.run_state_sha256 = run::Sha256Hex(checkpoint.run_state);
    std::vector<v1::PutCheckpointRequest> requests;
    for (v1::CheckpointPiece& piece : services::CheckpointToPieces(checkpoint)) {
      *requests.emplace_back().mutable_checkpoint() = std::move(piece);
    }
    *requests.front().mutable_lease() = services::LeaseToProto(run.key);
    v1::EvaluationLog log;
    requests.front().set_evaluation_log(log.SerializeAsString());
    Upload<v1::PutCheckpointRequest, v1::PutCheckpointResponse>(
        "PutCheckpoint", std::move(requests),
        &CoordinatorService::Stub::async::PutCheckpoint,
        [this, name](const grpc::Status&) { Evaluated(name); });
  }

  void Evaluated(const std::string& name) {
    if (auto found = runs_.find(name); found != runs_.end()) found->second.evaluating = false;
  }

  void Finish(const std::string& name) {
    const run::LeaseKey key = runs_.at(name).key;
    runs_.erase(name);
    leases_.erase(name);
    v1::FinishRunRequest request;
    *request.mutable_lease() = services::LeaseToProto(key);
    request.set_state(v1::RUN_STATE_COMPLETED);
    Unary<v1::FinishRunRequest, v1::FinishRunResponse>(
        "FinishRun", kLearnerRpcTimeout, request,
        &CoordinatorService::Stub::async::FinishRun,
        [](const grpc::Status&, const v1::FinishRunResponse&) {});
  }

  std::map<std::string, Held> leases_;
  std::map<std::string, Run> runs_;  // by learner lease
};

// CPU seconds (user + system) of process `pid`, from /proc/<pid>/stat.
double CpuSeconds(int pid) {
  std::ifstream stat(absl::StrCat("/proc/", pid, "/stat"));
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  std::istringstream fields(text.substr(text.rfind(')') + 2));
  std::string field;
  double ticks = 0;
  for (int i = 3; i <= 15 && fields >> field; ++i) {
    if (i == 14 || i == 15) ticks += std::stod(field);  // utime, stime
  }
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// A field of /proc/<pid>/status in MiB (VmRSS, VmHWM).
double StatusMiB(int pid, const std::string& field) {
  std::ifstream status(absl::StrCat("/proc/", pid, "/status"));
  for (std::string line; std::getline(status, line);) {
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1)) / 1024;
  }
  return NAN;
}

// The calls' policy and checkpoint: a CartPole network's sizes, any bytes.
std::string PolicyBytes() {
  v1::PolicyWeights weights;
  weights.set_num_actions(2);
  v1::DenseLayer& layer = *weights.add_layers();
  layer.mutable_weight()->add_shape(kPolicyFloats);
  layer.mutable_weight()->set_data(std::string(4 * kPolicyFloats, '\1'));
  return weights.SerializeAsString();
}

int Main(int argc, char** argv) {
  Options options;
  CLI::App app{"fleet_benchmark: a simulated fleet of actors and learners on one coordinator"};
  app.add_option("--coordinator", options.coordinator, "host:port")->required();
  app.add_option("--pid", options.coordinator_pid, "the coordinator's process id")->required();
  app.add_option("--sweep-spec", options.sweep_spec, "the sweep to submit (YAML)")->required();
  app.add_option("--actors", options.actors)->capture_default_str();
  app.add_option("--learners", options.learners)->capture_default_str();
  app.add_option("--runs-per-learner", options.runs_per_learner)->capture_default_str();
  app.add_option("--slot-steps-per-second", options.slot_steps_per_second,
                 "environment steps a slot collects per second")
      ->capture_default_str();
  app.add_option("--job-seconds", options.job_seconds, "an evaluation job's time on an actor")
      ->capture_default_str();
  app.add_option("--warmup", options.warmup_s, "seconds before the window")->capture_default_str();
  app.add_option("--seconds", options.seconds, "the measured window")->capture_default_str();
  app.add_option("--ramp", options.ramp_s, "seconds over which the workers start")
      ->capture_default_str();
  app.add_option("--threads", options.threads, "event loops")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  Fleet fleet{.options = options};
  for (int i = 0; i < options.threads; ++i) fleet.loops.push_back(std::make_unique<EventLoop>());
  fleet.policy = PolicyBytes();
  fleet.learner_bin.assign(kLearnerBinBytes, '\2');

  // The sweep first, as a user submits it before the fleet has work.
  absl::StatusOr<std::string> spec = ReadFile(options.sweep_spec);
  if (!spec.ok()) {
    std::fprintf(stderr, "fleet_benchmark: error: %s\n", spec.status().ToString().c_str());
    return 1;
  }
  {
    auto stub = CoordinatorService::NewStub(WorkerChannel(options.coordinator));
    grpc::ClientContext context;
    // A sweep of thousands of runs takes a while: each run's directory is written and synced.
    context.set_deadline(absl::ToChronoTime(absl::Now() + absl::Minutes(10)));
    v1::SubmitSweepRequest request;
    request.set_request_id("fleet");
    request.set_spec(*spec);
    request.set_spec_name(options.sweep_spec);
    v1::SubmitSweepResponse response;
    if (const grpc::Status status = stub->SubmitSweep(&context, request, &response);
        !status.ok()) {
      std::fprintf(stderr, "fleet_benchmark: error: SubmitSweep: %s\n",
                   status.error_message().c_str());
      return 1;
    }
  }

  std::vector<std::unique_ptr<Worker>> workers;
  for (int i = 0; i < options.learners; ++i) {
    workers.push_back(std::make_unique<Learner>(fleet, i, absl::StrCat("learner-", i)));
  }
  for (int i = 0; i < options.actors; ++i) {
    workers.push_back(std::make_unique<Actor>(fleet, i, absl::StrCat("actor-", i)));
  }
  const absl::Time start = absl::Now();
  std::mt19937 random(0);
  std::shuffle(workers.begin(), workers.end(), random);
  for (size_t i = 0; i < workers.size(); ++i) {
    absl::SleepFor(absl::Seconds(options.ramp_s) / static_cast<double>(workers.size()));
    workers[i]->Start();
  }
  absl::SleepFor(start + absl::Seconds(options.warmup_s) - absl::Now());

  const int pid = options.coordinator_pid;
  const double cpu_start = CpuSeconds(pid);
  const double own_start = CpuSeconds(getpid());
  const absl::Time window_start = absl::Now();
  fleet.latencies.Start();
  double rss_max = 0;
  while (absl::Now() < window_start + absl::Seconds(options.seconds)) {
    absl::SleepFor(absl::Seconds(1));
    rss_max = std::max(rss_max, StatusMiB(pid, "VmRSS"));
  }
  std::map<std::string, Latencies::Figures> methods = fleet.latencies.Stop();
  const double window = absl::ToDoubleSeconds(absl::Now() - window_start);
  const double cores = (CpuSeconds(pid) - cpu_start) / window;
  const double own_cores = (CpuSeconds(getpid()) - own_start) / window;
  const double rss = StatusMiB(pid, "VmRSS");
  const double hwm = StatusMiB(pid, "VmHWM");

  int64_t calls = 0;
  int64_t failed = 0;
  std::vector<double> lease_ms;  // renewals, releases, and acquisitions that granted a lease
  std::vector<double> overrun_ms;
  for (auto& [method, figures] : methods) {
    calls += figures.calls;
    failed += figures.failed;
    overrun_ms.insert(overrun_ms.end(), figures.overrun_ms.begin(), figures.overrun_ms.end());
  }
  for (const char* method : {"RenewLease", "ReleaseLease"}) {
    lease_ms.insert(lease_ms.end(), methods[method].ms.begin(), methods[method].ms.end());
  }
  const std::vector<double>& renew = methods["RenewLease"].ms;
  // | fleet | calls/s | renew p50 | renew p99 | lease p99 | poll overrun p99 | failed |
  // coordinator cores | RSS | peak | simulator cores |
  std::printf("| %d / %d | %.0f | %.1f | %.1f | %.1f | %.1f | %lld | %.2f | %.0f | %.0f | "
              "%.2f |\n",
              options.actors, options.learners, calls / window,
              Quantile(renew, 0.5), Quantile(renew, 0.99), Quantile(lease_ms, 0.99),
              Quantile(overrun_ms, 0.99), static_cast<long long>(failed), cores, rss, hwm,
              own_cores);
  std::printf("method              calls/s     p50 ms     p99 ms  overrun p99  failed\n");
  for (auto& [method, figures] : methods) {
    std::string codes;
    for (const auto& [code, count] : figures.codes) absl::StrAppend(&codes, " ", code, "x", count);
    std::printf("%-18s %8.1f %10.2f %10.2f %12.1f %7lld%s\n", method.c_str(),
                figures.calls / window, Quantile(figures.ms, 0.5), Quantile(figures.ms, 0.99),
                Quantile(figures.overrun_ms, 0.99), static_cast<long long>(figures.failed),
                codes.c_str());
  }
  std::printf("window %.0f s; coordinator RSS max in window %.0f MiB\n", window, rss_max);
  std::fflush(stdout);

  // Stop: no new calls; the ones in flight end within their waits and deadlines.
  fleet.stopping = true;
  const absl::Time deadline = absl::Now() + absl::Seconds(15);
  while (fleet.in_flight > 0 && absl::Now() < deadline) absl::SleepFor(absl::Milliseconds(50));
  if (fleet.in_flight > 0) std::_Exit(0);  // calls outlasting the coordinator's answers
  fleet.loops.clear();
  return 0;
}

}  // namespace
}  // namespace dcs::bench

int main(int argc, char** argv) { return dcs::bench::Main(argc, argv); }
