# DCS's layers, bottom up: the one table of the layering rule (cmake/layering.cmake checks it;
# docs/architecture.md §1 draws it). A library or program may link DCS libraries of lower
# layers only; gRPC, libtorch and SQLite (the coordinator's store) only where marked. Those of
# one layer do not link each other. The learner and the actor link no store.
dcs_layer(dcs_common 0)             # status macros, seed streams, small utilities
dcs_layer(dcs_proto 0)              # protobuf messages of the wire contract
dcs_layer(dcs_env 1)                # environments, schedules, the dynamic-context wrapper
dcs_layer(dcs_proto_grpc 1 GRPC)    # gRPC stubs of the wire contract
dcs_layer(dcs_actor 2)              # policies, rollout collection, evaluation
dcs_layer(dcs_run 3)                # a run as data: configs, plans, records
dcs_layer(dcs-config-reference 4)   # tools/: docs/config.md from the config readers' tables
dcs_layer(dcs_learner 4 TORCH)      # PPO in libtorch, training sessions
dcs_layer(dcs_coordinator 4 SQLITE) # workers, the run store and leases, samplers, study drivers
dcs_layer(dcs_report 5 SQLITE)      # reports, their statistics and figures, for the client
dcs_layer(dcs_services 5 GRPC)      # the servers' plumbing, shared with the client
dcs_layer(dcs_coordinator_service 6 GRPC SQLITE)  # CoordinatorService over the store
dcs_layer(dcs_learner_service 6 GRPC TORCH)  # runs hosted for actors, LearnerService
dcs_layer(dcs_actor_service 6 GRPC) # env slots stepped for learners
# The servers beside the client library, so that none of them links it; the client above.
dcs_layer(dcs-coordinator 7 GRPC SQLITE)
dcs_layer(dcs-learner 7 GRPC TORCH)
dcs_layer(dcs-actor 7 GRPC)
dcs_layer(dcs_cli 7 GRPC SQLITE)    # the dcs client's commands
dcs_layer(dcs 8 GRPC SQLITE)        # the client, without libtorch: it hands training over to
dcs_layer(dcs-train 8 GRPC TORCH SQLITE)  # the same client with libtorch
