# Compiler settings shared by every DCS target (not by generated protobuf code).
include(GoogleTest)
function(dcs_target_options target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Werror
    -Werror=unused-result
    # GCC 12 reports false -Wrestrict positives inside libstdc++'s std::string at -O3
    # (https://gcc.gnu.org/bugzilla/show_bug.cgi?id=105329); clang has no such warning (and
    # refuses to be told of one it does not know: the fuzz build, cmake/fuzzing.cmake).
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>
    # Designated initialisers that name only some fields are how options structs are filled.
    -Wno-missing-field-initializers)
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
endfunction()

# dcs_library(name SOURCES ... DEPS ...): the one library of a folder. It needs a layer in
# cmake/layers.cmake (cmake/layering.cmake refuses the build otherwise).
function(dcs_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  set_property(GLOBAL APPEND PROPERTY DCS_LIBRARIES ${name})
  add_library(${name} STATIC ${ARG_SOURCES})
  dcs_target_options(${name})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
endfunction()

# dcs_test(name SOURCES ... DEPS ... [LABELS ...]): a GoogleTest binary registered with ctest.
function(dcs_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  dcs_target_options(${name})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gmock GTest::gtest_main)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${ARG_LABELS}")
endfunction()
