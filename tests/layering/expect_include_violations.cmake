# Runs cmake/check_includes.cmake over tests/layering/stray_includes/ and fails unless it
# refuses exactly the stray includes there, each with its reason.
#   cmake -DCHECK=<check_includes.cmake> -DSOURCE_ROOT=<stray_includes> -DLAYERS=<file> -P ...
execute_process(
  COMMAND ${CMAKE_COMMAND} -DSOURCE_ROOT=${SOURCE_ROOT} -DLAYERS=${LAYERS} -P ${CHECK}
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
string(REGEX REPLACE "[ \n]+" " " output "${output}")  # CMake wraps long messages
if(result EQUAL 0)
  message(FATAL_ERROR "the include check accepted stray includes: ${output}")
endif()
foreach(expected
    "6 include\\(s\\) break the layering"
    "env/stray.cc: includes learner/ppo_learner.h, of dcs_learner \\(layer 4\\), not below"
    "env/stray.cc: includes grpcpp/grpcpp.h, a gRPC header, and dcs_env must not use gRPC"
    "env/stray.cc: includes tests/testing/temp_dir.h, a test's header"
    "coordinator/stray.cc: includes learner/training_session.h, of dcs_learner \\(layer 4\\), not"
    "coordinator/stray.cc: includes torch/torch.h, a libtorch header, and dcs_coordinator must not"
    "coordinator/stray.cc: includes dcs/v1/coordinator_service.grpc.pb.h, a gRPC header")
  if(NOT output MATCHES "${expected}")
    message(FATAL_ERROR "expected '${expected}' in: ${output}")
  endif()
endforeach()
