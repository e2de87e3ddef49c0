// Copyright 2026 The DCS Authors.
//
// CoordinatorService's watches: a run, or a sweep with its runs, streamed to a client as it
// changes (services/coordinator/watchers.h says when a watch looks at the store again).

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "absl/base/thread_annotations.h"
#include "absl/strings/str_cat.h"
#include "absl/synchronization/mutex.h"
#include "common/status_macros.h"
#include "google/protobuf/util/message_differencer.h"
#include "services/coordinator/coordinator_service.h"
#include "services/coordinator/record_proto.h"
#include "services/grpc_status.h"
#include "services/run_proto.h"

namespace dcs::services {
namespace {

// A watch's stream. Each look reads the update (`read`: every store read of one update) and
// writes it if it differs from the last one written; the update that shows the end is written
// with the call's OK. One write at a time: a look while one is in flight only asks to look
// again once it is done, so a slow client gets the latest state, not a backlog. Owned by gRPC
// from construction until OnDone; looks run on the watchers' thread, the rest on gRPC's.
template <typename Update>
class WatchWriter final : public grpc::ServerWriteReactor<Update> {
 public:
  struct Watch {
    std::vector<std::string> topics;  // what it follows before its first look
    absl::Duration min_interval;      // between two looks
    std::function<absl::StatusOr<Update>()> read;
    std::function<std::vector<std::string>(const Update&)> follows;  // after each look
    std::function<bool(const Update&)> ended;
    std::function<void(const absl::Status&)> count_refusal;  // a read's error ends the call
  };

  // Counts itself in `open` while it lives.
  WatchWriter(Watchers& watchers, Watch watch, prometheus::Gauge& open)
      : watchers_(watchers), watch_(std::move(watch)), open_(open) {
    open_.Increment();
    id_ = watchers_.Add(
        watch_.topics, watch_.min_interval, [this] { Look(); },
        [this] {
          End(absl::UnavailableError("the coordinator is stopping: watch again once it is back"));
        });
    watchers_.Touch(id_);  // the first look: the state now
  }

  void OnWriteDone(bool ok) override {
    bool look_again = false;
    {
      absl::MutexLock lock(&mu_);
      writing_ = false;
      if (!ok) {
        FinishLocked(absl::CancelledError("the watcher went"));
        return;
      }
      look_again = std::exchange(stale_, false);
    }
    if (look_again) watchers_.Touch(id_);
  }

  void OnCancel() override { End(absl::CancelledError("the watcher went")); }

  void OnDone() override {
    watchers_.Remove(id_);
    open_.Decrement();
    delete this;
  }

 private:
  void Look() {
    {
      absl::MutexLock lock(&mu_);
      if (finished_) return;
      if (writing_) {
        stale_ = true;
        return;
      }
    }
    absl::StatusOr<Update> update = watch_.read();
    if (update.ok()) watchers_.Follow(id_, watch_.follows(*update));
    absl::MutexLock lock(&mu_);
    if (finished_) return;
    if (!update.ok()) {
      watch_.count_refusal(update.status());
      FinishLocked(update.status());
      return;
    }
    if (sent_.has_value() &&
        google::protobuf::util::MessageDifferencer::Equals(*sent_, *update)) {
      return;
    }
    sent_ = *std::move(update);  // unchanged until written: no write is in flight
    if (watch_.ended(*sent_)) {
      finished_ = true;
      this->StartWriteAndFinish(&*sent_, grpc::WriteOptions(), grpc::Status::OK);
      return;
    }
    writing_ = true;
    this->StartWrite(&*sent_);
  }

  void End(const absl::Status& status) {
    absl::MutexLock lock(&mu_);
    FinishLocked(status);
  }

  void FinishLocked(const absl::Status& status) ABSL_EXCLUSIVE_LOCKS_REQUIRED(mu_) {
    if (finished_) return;
    finished_ = true;
    this->Finish(ToGrpcStatus(status));
  }

  Watchers& watchers_;
  const Watch watch_;
  prometheus::Gauge& open_;
  int64_t id_ = 0;  // set before the first look

  absl::Mutex mu_;
  std::optional<Update> sent_ ABSL_GUARDED_BY(mu_);  // the last update written, or in flight
  bool writing_ ABSL_GUARDED_BY(mu_) = false;
  bool stale_ ABSL_GUARDED_BY(mu_) = false;  // looked while writing: look again once written
  bool finished_ ABSL_GUARDED_BY(mu_) = false;
};

}  // namespace

std::string CoordinatorService::RunTopic(absl::string_view run_id) {
  return absl::StrCat("run ", run_id);
}

std::string CoordinatorService::SweepTopic(absl::string_view sweep_id) {
  return absl::StrCat("sweep ", sweep_id);
}

absl::StatusOr<v1::GetRunResponse> CoordinatorService::ReadRun(const std::string& run_id) const {
  DCS_ASSIGN_OR_RETURN(const coordinator::RunRecord run, runs_.store->runs().GetRun(run_id));
  v1::GetRunResponse response;
  *response.mutable_run() = RunToProto(run);
  return response;
}

absl::StatusOr<v1::GetSweepResponse> CoordinatorService::ReadSweep(
    const std::string& sweep_id) const {
  DCS_ASSIGN_OR_RETURN(const coordinator::SweepRecord sweep,
                       runs_.store->sweeps().GetSweep(sweep_id));
  DCS_ASSIGN_OR_RETURN(const std::vector<coordinator::RunRecord> runs,
                       runs_.store->sweeps().ListSweepRuns(sweep_id));
  v1::GetSweepResponse response;
  *response.mutable_sweep() = SweepToProto(sweep);
  for (const coordinator::RunRecord& run : runs) *response.add_runs() = RunToProto(run);
  return response;
}

grpc::ServerWriteReactor<v1::GetRunResponse>* CoordinatorService::WatchRun(
    grpc::CallbackServerContext* context, const v1::WatchRunRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::GetRunResponse>>(context, [&] {
    const std::string topic = RunTopic(request->run_id());
    return new WatchWriter<v1::GetRunResponse>(
        watchers_,
        {.topics = {topic},
         .min_interval = kRunWatchInterval,
         .read = [this, run_id = request->run_id()] { return ReadRun(run_id); },
         .follows = [topic](const v1::GetRunResponse&) { return std::vector{topic}; },
         .ended = [](const v1::GetRunResponse& run) { return RunEnded(run.run().state()); },
         .count_refusal = [this](const absl::Status& status) { rejected_.Count(status); }},
        run_watchers_);
  });
}

grpc::ServerWriteReactor<v1::GetSweepResponse>* CoordinatorService::WatchSweep(
    grpc::CallbackServerContext* context, const v1::WatchSweepRequest* request) {
  return calls_.Serve<grpc::ServerWriteReactor<v1::GetSweepResponse>>(context, [&] {
    const std::string topic = SweepTopic(request->sweep_id());
    return new WatchWriter<v1::GetSweepResponse>(
        watchers_,
        {.topics = {topic},
         .min_interval = kSweepWatchInterval,
         .read = [this, sweep_id = request->sweep_id()] { return ReadSweep(sweep_id); },
         // Its runs change without its writers knowing the sweep (a learner's progress).
         .follows =
             [topic](const v1::GetSweepResponse& sweep) {
               std::vector<std::string> topics = {topic};
               for (const v1::Run& run : sweep.runs()) topics.push_back(RunTopic(run.run_id()));
               return topics;
             },
         .ended =
             [](const v1::GetSweepResponse& sweep) { return SweepEnded(sweep.sweep().state()); },
         .count_refusal = [this](const absl::Status& status) { rejected_.Count(status); }},
        sweep_watchers_);
  });
}

void CoordinatorService::StopWatches() { watchers_.Close(); }

}  // namespace dcs::services
