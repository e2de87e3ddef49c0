// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_CLUSTER_CLIENT_H_
#define DCS_SERVICES_CLI_CLUSTER_CLIENT_H_

// The calls that the `dcs` client, `dcs up` and the tests make to a running cluster: health
// checks and the coordinator's status; and where the coordinator is. Each call opens its own
// channel and sets a deadline. Thread-safe.

#include <string>

#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "dcs/v1/coordinator_service.pb.h"
#include "services/cli/cli_command.h"

namespace dcs::services::cli {

// The coordinator's address: --addr (or DCS_ADDR), else the local cluster's in --data-dir
// (`dcs up`), else 127.0.0.1:50051.
std::string CoordinatorAddress(const GlobalFlags& flags);

// The token `dcs` presents (services/auth.h): --token-file's, else $DCS_TOKEN, else, when it
// calls the local cluster's coordinator (no --addr, or the same address), the local cluster's
// (its data directory's `token`); "" if none. Errors as LoadToken's.
absl::StatusOr<std::string> ClientToken(const GlobalFlags& flags);

// Asks the server at `address` (host:port) whether `service` is SERVING ("" = the whole
// server). UNAVAILABLE or DEADLINE_EXCEEDED if it cannot be reached; NOT_FOUND if it does not
// know `service`.
absl::StatusOr<bool> IsServing(const std::string& address, const std::string& service,
                               absl::Duration timeout);

// Polls IsServing until it returns true. DEADLINE_EXCEEDED after `timeout`, with the last
// answer in the message.
absl::Status WaitUntilServing(const std::string& address, const std::string& service,
                              absl::Duration timeout);

// The coordinator's view of the cluster. Errors as IsServing.
absl::StatusOr<v1::GetClusterStatusResponse> GetClusterStatus(const std::string& address,
                                                              absl::Duration timeout);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_CLUSTER_CLIENT_H_
