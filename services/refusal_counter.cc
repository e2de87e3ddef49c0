// Copyright 2026 The DCS Authors.
#include "services/refusal_counter.h"

namespace dcs::services {

RefusalCounter::RefusalCounter(prometheus::Registry& registry, const char* name, const char* help)
    : family_(prometheus::BuildCounter().Name(name).Help(help).Register(registry)) {
  for (const absl::StatusCode code :
       {absl::StatusCode::kInvalidArgument, absl::StatusCode::kNotFound,
        absl::StatusCode::kFailedPrecondition}) {
    family_.Add({{"reason", absl::StatusCodeToString(code)}});
  }
}

void RefusalCounter::Count(const absl::Status& status) {
  if (!status.ok()) family_.Add({{"reason", absl::StatusCodeToString(status.code())}}).Increment();
}

}  // namespace dcs::services
