// Copyright 2026 The DCS Authors.
#include "coordinator/lease_reaper.h"

namespace dcs::coordinator {

LeaseReaper::LeaseReaper(Store& store) : store_(store), counted_(store.LeasesLapsed()) {}

LeaseReaper::Reaped LeaseReaper::Tick(absl::Time now) {
  Reaped reaped{.status = store_.ExpireLeases(now).status()};
  const int64_t counted = store_.LeasesLapsed();
  reaped.lapsed = counted - counted_;
  counted_ = counted;
  return reaped;
}

}  // namespace dcs::coordinator
