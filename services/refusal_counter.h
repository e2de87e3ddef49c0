// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_REFUSAL_COUNTER_H_
#define DCS_SERVICES_REFUSAL_COUNTER_H_

// A counter of refused requests by reason, the status code's name (`reason="NOT_FOUND"`). The
// reasons a DCS server refuses with in normal operation (INVALID_ARGUMENT, NOT_FOUND,
// FAILED_PRECONDITION) start at zero, so that rate() sees their first refusal and dashboards
// show a zero rather than no data. Thread-safe. Borrows the registry,
// which must outlive it.

#include <prometheus/counter.h>
#include <prometheus/family.h>
#include <prometheus/registry.h>

#include "absl/status/status.h"

namespace dcs::services {

class RefusalCounter {
 public:
  RefusalCounter(prometheus::Registry& registry, const char* name, const char* help);

  // Counts `status` under its code if it is not OK.
  void Count(const absl::Status& status);

 private:
  prometheus::Family<prometheus::Counter>& family_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_REFUSAL_COUNTER_H_
