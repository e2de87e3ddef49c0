// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_COORDINATOR_STUDY_PROTO_H_
#define DCS_SERVICES_COORDINATOR_STUDY_PROTO_H_

// Conversions between the coordinator's studies (coordinator/study_table.h) and dcs.v1 messages,
// both ways: the coordinator sends what the client reads. Thread-safe (pure functions).

#include "absl/status/statusor.h"
#include "coordinator/study_table.h"
#include "dcs/v1/study.pb.h"

namespace dcs::services {

v1::StudyTrial StudyTrialToProto(const coordinator::StudyTrial& trial);
// INVALID_ARGUMENT for an unknown state.
absl::StatusOr<coordinator::StudyTrial> StudyTrialFromProto(const v1::StudyTrial& proto);

v1::Study StudyToProto(const coordinator::StudyRecord& study);
// INVALID_ARGUMENT for an unknown sampler, direction or trial state.
absl::StatusOr<coordinator::StudyRecord> StudyFromProto(const v1::Study& proto);

}  // namespace dcs::services

#endif  // DCS_SERVICES_COORDINATOR_STUDY_PROTO_H_
