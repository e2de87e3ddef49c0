// Copyright 2026 The DCS Authors.
#include "services/lease_renewals.h"

#include <grpcpp/grpcpp.h>

#include <memory>
#include <utility>

#include "absl/synchronization/blocking_counter.h"
#include "common/status_util.h"
#include "services/channel.h"
#include "services/grpc_status.h"
#include "services/run_proto.h"
#include "services/time_proto.h"

namespace dcs::services {

std::vector<absl::StatusOr<absl::Duration>> RenewLeases(v1::CoordinatorService::Stub& coordinator,
                                                        absl::Span<const run::LeaseKey> leases,
                                                        absl::Duration timeout) {
  struct Call {
    grpc::ClientContext context;
    v1::RenewLeaseRequest request;
    v1::RenewLeaseResponse response;
    grpc::Status status;
  };
  std::vector<std::unique_ptr<Call>> calls;
  absl::BlockingCounter pending(static_cast<int>(leases.size()));
  for (const run::LeaseKey& lease : leases) {
    Call& call = *calls.emplace_back(std::make_unique<Call>());
    *call.request.mutable_lease() = LeaseToProto(lease);
    SetTimeout(call.context, timeout);
    coordinator.async()->RenewLease(&call.context, &call.request, &call.response,
                                    [&pending, &call](grpc::Status status) {
                                      call.status = std::move(status);
                                      pending.DecrementCount();
                                    });
  }
  pending.Wait();
  std::vector<absl::StatusOr<absl::Duration>> renewed;
  renewed.reserve(calls.size());
  for (const std::unique_ptr<Call>& call : calls) {
    if (call->status.ok()) {
      renewed.push_back(DurationFromProto(call->response.lease_duration()));
    } else {
      renewed.push_back(Annotate(FromGrpcStatus(call->status), "coordinator"));
    }
  }
  return renewed;
}

}  // namespace dcs::services
