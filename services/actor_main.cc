// Copyright 2026 The DCS Authors.
//
// dcs-actor: a stateless cluster member that will step scheduled environments and stream
// trajectories to a learner.

#include "coordinator/worker_registry.h"
#include "env/library_versions.h"
#include "services/service_main.h"
#include "services/worker_role.h"

int main(int argc, char** argv) {
  dcs::services::WorkerServiceRole role(dcs::coordinator::WorkerRole::kActor);
  return dcs::services::RunService({.program = "dcs-actor",
                                    .component = "actor",
                                    .description = "dcs-actor: a DCS environment actor",
                                    .default_listen = "127.0.0.1:0",
                                    .default_metrics_listen = "127.0.0.1:0",
                                    .libraries = dcs::env::LibraryVersions()},
                                   role, argc, argv);
}
