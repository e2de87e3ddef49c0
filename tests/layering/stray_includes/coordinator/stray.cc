// Copyright 2026 The DCS Authors.
//
// Not built: includes that break the layering (see env/stray.cc).
#include "run/run_spec.h"                   // a lower layer: fine
#include "learner/training_session.h"       // a library of the same layer
#include <torch/torch.h>                    // libtorch outside learner/
#include "dcs/v1/coordinator_service.grpc.pb.h"  // gRPC stubs below services/
#include "dcs/v1/evaluation.pb.h"           // protobuf messages: fine
