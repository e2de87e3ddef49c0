// Copyright 2026 The DCS Authors.
#include "services/cluster_proto.h"

#include "absl/strings/str_cat.h"
#include "services/time_proto.h"

namespace dcs::services {
namespace {

void AddLibraries(const std::vector<LibraryVersion>& libraries, v1::BuildInfo* proto) {
  for (const LibraryVersion& library : libraries) {
    v1::LibraryVersion* entry = proto->add_libraries();
    entry->set_name(library.name);
    entry->set_version(library.version);
  }
}

}  // namespace

v1::BuildInfo BuildInfoToProto(const BuildInfo& build) {
  v1::BuildInfo proto;
  proto.set_version(build.version);
  AddLibraries(build.libraries, &proto);
  return proto;
}

v1::WorkerInfo WorkerInfoToProto(const WorkerInfo& info) {
  v1::WorkerInfo proto;
  proto.set_role(info.role == WorkerRole::kLearner ? v1::WORKER_ROLE_LEARNER
                                                   : v1::WORKER_ROLE_ACTOR);
  proto.set_address(info.address);
  proto.set_hostname(info.hostname);
  proto.set_pid(info.pid);
  proto.mutable_build()->set_version(info.version);
  AddLibraries(info.libraries, proto.mutable_build());
  return proto;
}

absl::StatusOr<WorkerInfo> WorkerInfoFromProto(const v1::WorkerInfo& proto) {
  WorkerInfo info;
  switch (proto.role()) {
    case v1::WORKER_ROLE_LEARNER: info.role = WorkerRole::kLearner; break;
    case v1::WORKER_ROLE_ACTOR: info.role = WorkerRole::kActor; break;
    default:
      return absl::InvalidArgumentError(absl::StrCat(
          "worker role must be WORKER_ROLE_LEARNER or WORKER_ROLE_ACTOR, got ",
          v1::WorkerRole_Name(proto.role()).empty() ? absl::StrCat(proto.role())
                                                    : v1::WorkerRole_Name(proto.role())));
  }
  info.address = proto.address();
  info.hostname = proto.hostname();
  info.pid = proto.pid();
  info.version = proto.build().version();
  for (const v1::LibraryVersion& library : proto.build().libraries()) {
    info.libraries.push_back({library.name(), library.version()});
  }
  return info;
}

}  // namespace dcs::services
