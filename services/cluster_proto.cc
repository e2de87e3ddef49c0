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

v1::WorkerInfo WorkerInfoToProto(const coordinator::WorkerInfo& info) {
  v1::WorkerInfo proto;
  proto.set_role(info.role == coordinator::WorkerRole::kLearner ? v1::WORKER_ROLE_LEARNER
                                                                : v1::WORKER_ROLE_ACTOR);
  proto.set_address(info.address);
  proto.set_hostname(info.hostname);
  proto.set_pid(info.pid);
  proto.mutable_build()->set_version(info.version);
  AddLibraries(info.libraries, proto.mutable_build());
  return proto;
}

absl::StatusOr<coordinator::WorkerInfo> WorkerInfoFromProto(const v1::WorkerInfo& proto) {
  coordinator::WorkerInfo info;
  switch (proto.role()) {
    case v1::WORKER_ROLE_LEARNER: info.role = coordinator::WorkerRole::kLearner; break;
    case v1::WORKER_ROLE_ACTOR: info.role = coordinator::WorkerRole::kActor; break;
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

v1::Worker WorkerToProto(const coordinator::WorkerRecord& record) {
  v1::Worker proto;
  proto.set_worker_id(record.id);
  *proto.mutable_info() = WorkerInfoToProto(record.info);
  proto.set_state(record.state == coordinator::WorkerState::kAlive ? v1::WORKER_STATE_ALIVE
                                                                   : v1::WORKER_STATE_LOST);
  *proto.mutable_registered_time() = TimeToProto(record.registered_at);
  *proto.mutable_last_heartbeat_time() = TimeToProto(record.last_heartbeat_at);
  return proto;
}

}  // namespace dcs::services
