// Copyright 2026 The DCS Authors.
//
// The latency of a cheap call while the coordinator commits: GetRun of one run, called back to
// back by one client, first on a quiet coordinator, then while `--writers` clients submit the
// sweep SPEC again and again without pause (each submission is one SQLite transaction with
// synchronous=FULL plus a directory and an fsynced config file per run). The number that
// matters is GetRun's p99 under commits: it measures whether cheap calls wait behind the
// store's work on gRPC's threads. Prints one line per phase.
// Usage: getrun_under_commits ADDRESS SPEC [--seconds S] [--writers W]

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <grpcpp/grpcpp.h>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "dcs/v1/coordinator_service.grpc.pb.h"
#include "services/channel.h"

namespace {

struct Latencies {
  std::vector<double> ms;
  int failures = 0;
};

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(q * static_cast<double>(values.size() - 1))];
}

// Submits one sweep; false if it failed.
bool SubmitSweep(dcs::v1::CoordinatorService::Stub& stub, const std::string& spec,
                 const std::string& request_id) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  dcs::v1::SubmitSweepRequest request;
  request.set_spec(spec);
  request.set_request_id(request_id);
  dcs::v1::SubmitSweepResponse response;
  return stub.SubmitSweep(&context, request, &response).ok();
}

Latencies TimeGetRun(dcs::v1::CoordinatorService::Stub& stub, const std::string& run_id,
                     absl::Duration duration) {
  Latencies latencies;
  const absl::Time end = absl::Now() + duration;
  dcs::v1::GetRunRequest request;
  request.set_run_id(run_id);
  while (absl::Now() < end) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(30));
    dcs::v1::GetRunResponse response;
    const absl::Time start = absl::Now();
    const grpc::Status status = stub.GetRun(&context, request, &response);
    latencies.ms.push_back(absl::ToDoubleMilliseconds(absl::Now() - start));
    if (!status.ok()) ++latencies.failures;
  }
  return latencies;
}

void Print(const char* phase, const Latencies& latencies, int sweeps) {
  std::printf("%-14s calls %6zu  failures %d  p50_ms %7.3f  p99_ms %8.3f  max_ms %8.3f  "
              "sweeps %d\n",
              phase, latencies.ms.size(), latencies.failures, Quantile(latencies.ms, 0.5),
              Quantile(latencies.ms, 0.99), Quantile(latencies.ms, 1.0), sweeps);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("GetRun's latency while the coordinator commits sweeps");
  std::string address;
  double seconds = 20;
  int writers = 2;
  std::string spec_file;
  app.add_option("address", address, "the coordinator's gRPC address")->required();
  app.add_option("spec", spec_file, "the sweep spec submitted")->required();
  app.add_option("--seconds", seconds, "length of each phase");
  app.add_option("--writers", writers, "clients submitting sweeps");
  CLI11_PARSE(app, argc, argv);

  auto stub = dcs::v1::CoordinatorService::NewStub(dcs::services::OpenChannel(address));
  const absl::StatusOr<std::string> spec = dcs::ReadFile(spec_file);
  if (!spec.ok()) {
    std::fprintf(stderr, "getrun_under_commits: %s\n", spec.status().ToString().c_str());
    return 1;
  }
  const std::string tag = absl::StrCat(absl::ToUnixNanos(absl::Now()));
  if (!SubmitSweep(*stub, *spec, absl::StrCat(tag, "-first"))) {
    std::fprintf(stderr, "getrun_under_commits: cannot submit a sweep to %s\n", address.c_str());
    return 1;
  }
  const std::string run_id = "run-1";
  const absl::Duration phase = absl::Seconds(seconds);
  Print("quiet", TimeGetRun(*stub, run_id, phase), 0);

  std::atomic<bool> stop = false;
  std::atomic<int> sweeps = 0;
  std::vector<std::thread> threads;
  for (int w = 0; w < writers; ++w) {
    threads.emplace_back([&, w] {
      auto writer = dcs::v1::CoordinatorService::NewStub(dcs::services::OpenChannel(address));
      for (int i = 0; !stop; ++i) {
        if (SubmitSweep(*writer, *spec, absl::StrCat(tag, "-", w, "-", i))) ++sweeps;
      }
    });
  }
  const Latencies loaded = TimeGetRun(*stub, run_id, phase);
  stop = true;
  for (std::thread& thread : threads) thread.join();
  Print("under_commits", loaded, sweeps);
  return 0;
}
