// Copyright 2026 The DCS Authors.
#include "tests/testing/in_process_coordinator.h"

#include <memory>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/time/clock.h"
#include "tests/testing/temp_dir.h"

namespace dcs::testing {

absl::StatusOr<std::unique_ptr<InProcessCoordinator>> InProcessCoordinator::Start(
    const InProcessCoordinatorOptions& options) {
  std::unique_ptr<InProcessCoordinator> coordinator(new InProcessCoordinator());
  absl::StatusOr<std::unique_ptr<coordinator::WorkerRegistry>> registry =
      coordinator::WorkerRegistry::Create(options.registry);
  if (!registry.ok()) return registry.status();
  coordinator->registry_ = *std::move(registry);
  const std::string data_dir = options.data_dir.empty() ? MakeTempDir() : options.data_dir;
  absl::StatusOr<std::unique_ptr<coordinator::Store>> store = coordinator::Store::Open(
      data_dir + "/coordinator.db", {.lease_duration = options.lease_duration}, absl::Now());
  if (!store.ok()) return store.status();
  coordinator->store_ = *std::move(store);
  coordinator->service_ = std::make_unique<services::CoordinatorService>(
      *coordinator->registry_,
      services::RunStorage{.store = coordinator->store_.get(),
                           .data_dir = data_dir,
                           .lease_duration = options.lease_duration},
      options.build, options.start_time.value_or(absl::Now()), *coordinator->metrics_);
  absl::StatusOr<std::unique_ptr<services::Server>> server = services::Server::Start(
      {.listen_address = options.listen_address,
       .services = {{.full_name = "dcs.v1.CoordinatorService",
                     .service = coordinator->service_.get()}},
       .metrics = coordinator->metrics_.get()});
  if (!server.ok()) return server.status();
  coordinator->server_ = *std::move(server);
  if (options.serving) coordinator->server_->SetServing(true);
  return coordinator;
}

InProcessCoordinator::~InProcessCoordinator() {
  if (server_ != nullptr) server_->Shutdown(absl::ZeroDuration());
}

std::string InProcessCoordinator::address() const {
  return absl::StrCat("127.0.0.1:", server_->port());
}

}  // namespace dcs::testing
