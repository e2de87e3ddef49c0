// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_DETACH_H_
#define DCS_SERVICES_CLI_DETACH_H_

// Ctrl-C while `dcs` follows work on a cluster (a run, a sweep) detaches rather than killing
// the client: the work goes on, and the command says how to follow it again. One at a time,
// on main's thread.

namespace dcs::services::cli {

// While alive, SIGINT and SIGTERM set requested() instead of ending the process.
class DetachOnInterrupt {
 public:
  DetachOnInterrupt();
  ~DetachOnInterrupt();
  DetachOnInterrupt(const DetachOnInterrupt&) = delete;
  DetachOnInterrupt& operator=(const DetachOnInterrupt&) = delete;

  // True once SIGINT or SIGTERM arrived. Async-signal-safe to set, safe to read anywhere.
  bool requested() const;
};

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_DETACH_H_
