# Configures the project with one more library linked into one target (DCS_EXTRA_LINK_FOR_TEST)
# and fails unless the configure step refuses it with `EXPECT` (a regular expression) in its
# error: the link check of cmake/layering.cmake, shown to bite.
#   cmake -DPROJECT=<source dir> -DBUILD=<scratch dir> -DGENERATOR=<generator>
#         -DLINK=<target>=<library> -DEXPECT=<regex> -P expect_configure_failure.cmake
file(REMOVE_RECURSE "${BUILD}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${PROJECT} -B ${BUILD} -G ${GENERATOR}
          -DDCS_BUILD_TESTS=OFF -DDCS_BUILD_BENCHMARKS=OFF "-DDCS_EXTRA_LINK_FOR_TEST=${LINK}"
  RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
file(REMOVE_RECURSE "${BUILD}")
string(REGEX REPLACE "[ \n]+" " " output "${output}")  # CMake wraps long messages
if(result EQUAL 0)
  message(FATAL_ERROR "the configure step accepted ${LINK}")
endif()
if(NOT output MATCHES "${EXPECT}")
  message(FATAL_ERROR "expected '${EXPECT}' in: ${output}")
endif()
