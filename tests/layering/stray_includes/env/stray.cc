// Copyright 2026 The DCS Authors.
//
// Not built: includes that break the layering, for tests/layering/expect_include_violations.cmake
// to see cmake/check_includes.cmake refuse each one.
#include "env/cartpole.h"           // its own folder: fine
#include "common/random.h"          // a lower layer: fine
#include "learner/ppo_learner.h"    // a higher layer
#include <grpcpp/grpcpp.h>          // gRPC below services/
#include "tests/testing/temp_dir.h" // test code in a library
