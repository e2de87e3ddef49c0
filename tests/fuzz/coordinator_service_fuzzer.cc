// Copyright 2026 The DCS Authors.
// Fuzzes every request handler of the coordinator's service (services/coordinator/coordinator_service.h):
// the real CoordinatorService over a SQLite store and a data directory of its own, served
// in-process by a gRPC server; each input is one call of one of its methods, with the cluster's
// token, so that it passes authentication and reaches the handler (tests/fuzz/fuzzed_call.h
// says how an input names the method and its requests). The seeds are valid requests of every
// method (tests/fuzz/make_service_seeds.py): a run and a sweep submitted, leases, checkpoints,
// evaluations, a study.
// Calls change the store, and later inputs see what earlier ones left (runs, leases), as a
// coordinator sees a stream of clients; every 2,000 inputs the coordinator starts afresh, so
// that the store stays small and an input's effect depends on a bounded past.
// Asserts: every call ends with a status the service chose (no crash, leak, sanitizer report
// or escaped exception: gRPC would say UNKNOWN), within its deadline.

#include <grpcpp/server.h>
#include <grpcpp/server_builder.h>
#include <google/protobuf/descriptor.h>
#include <prometheus/registry.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "coordinator/store.h"
#include "coordinator/worker_registry.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/auth.h"
#include "services/build_info.h"
#include "services/coordinator/coordinator_service.h"
#include "tests/fuzz/fuzz_check.h"
#include "tests/fuzz/fuzzed_call.h"
#include "tests/fuzz/scratch_dir.h"

namespace dcs::fuzz {
namespace {

constexpr char kToken[] = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";
constexpr int kInputsPerCoordinator = 2000;
// Far above what any call takes here: a call that reaches it hangs.
constexpr absl::Duration kCallTimeout = absl::Seconds(20);

// A coordinator served in-process, over a new store in a new data directory.
class Coordinator {
 public:
  explicit Coordinator(int generation) {
    data_dir_ = absl::StrCat(ScratchDir(), "/coordinator-", generation);
    std::filesystem::create_directories(data_dir_);
    absl::StatusOr<std::unique_ptr<coordinator::WorkerRegistry>> registry =
        coordinator::WorkerRegistry::Create({});
    DCS_FUZZ_CHECK(registry.ok(), registry.status());
    registry_ = *std::move(registry);
    absl::StatusOr<std::unique_ptr<coordinator::Store>> store =
        coordinator::Store::Open(data_dir_ + "/coordinator.db", {}, absl::Now());
    DCS_FUZZ_CHECK(store.ok(), store.status());
    store_ = *std::move(store);
    service_ = std::make_unique<services::CoordinatorService>(
        *registry_, services::RunStorage{.store = store_.get(), .data_dir = data_dir_},
        services::ProcessBuildInfo({}), absl::Now(), metrics_);
    grpc::ServerBuilder builder;
    builder.RegisterService(service_.get());
    server_ = builder.BuildAndStart();
    DCS_FUZZ_CHECK(server_ != nullptr, absl::InternalError("the server did not start"));
    channel_ = server_->InProcessChannel({});
  }

  ~Coordinator() {
    server_->Shutdown(std::chrono::system_clock::now());
    server_->Wait();
    channel_.reset();
    server_.reset();
    service_.reset();
    store_.reset();
    std::error_code ignored;
    std::filesystem::remove_all(data_dir_, ignored);
  }

  const std::shared_ptr<grpc::Channel>& channel() const { return channel_; }

 private:
  std::string data_dir_;
  prometheus::Registry metrics_;
  std::unique_ptr<coordinator::WorkerRegistry> registry_;
  std::unique_ptr<coordinator::Store> store_;
  std::unique_ptr<services::CoordinatorService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
};

void FuzzCoordinatorCall(absl::string_view input) {
  static int inputs = 0;
  static int generation = 0;
  // Never destroyed: gRPC's own threads may outlive static destructors.
  static Coordinator* coordinator = nullptr;
  if (inputs++ % kInputsPerCoordinator == 0) {
    if (coordinator == nullptr) services::SetClusterToken(kToken);
    delete coordinator;
    coordinator = new Coordinator(generation++);
  }
  static const google::protobuf::ServiceDescriptor& service =
      *google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(
          v1::CoordinatorService::service_full_name());
  const FuzzedCall call = DecodeCall(service, input);
  // A watch streams until its run or sweep ends, which none does here (there are no workers):
  // its first message, or its error, is its answer.
  const bool watch = absl::StartsWith(call.method->name(), "Watch");
  const absl::Time start = absl::Now();
  const grpc::Status status = MakeCall(coordinator->channel(), call, kToken, kCallTimeout,
                                       watch ? 1 : std::numeric_limits<int>::max());
  DCS_FUZZ_CHECK(
      status.error_code() != grpc::StatusCode::UNKNOWN &&
          status.error_code() != grpc::StatusCode::DEADLINE_EXCEEDED,
      absl::UnknownError(absl::StrCat(call.method->name(), ": ", status.error_message(), " after ",
                                      absl::FormatDuration(absl::Now() - start))));
}

}  // namespace
}  // namespace dcs::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dcs::fuzz::FuzzCoordinatorCall(absl::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
