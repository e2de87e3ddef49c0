# The fuzz build (DCS_FUZZ=ON; tests/fuzz/README.md says how to run it): a build directory of
# its own, configured with Debian's clang (libFuzzer ships only with clang), in which every DCS
# target is instrumented for libFuzzer's coverage and checked by AddressSanitizer and
# UndefinedBehaviorSanitizer; the fuzz targets link libFuzzer's main (tests/fuzz/CMakeLists.txt).
# Only the fuzz targets and the libraries they use are built: the library folders are added
# EXCLUDE_FROM_ALL, and tests/ and bench/ not at all. Third-party libraries stay as Debian built
# them (uninstrumented): what is fuzzed is DCS's code.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "DCS_FUZZ needs clang (libFuzzer); configure with "
                      "-DCMAKE_CXX_COMPILER=clang++-14 (scripts/bootstrap installs it).")
endif()

# The build type of a fuzz build: optimised enough to run fast, assertions kept, stack traces
# with file and line.
set(CMAKE_CXX_FLAGS_FUZZ "-O1 -gline-tables-only" CACHE STRING "C++ flags of the Fuzz build type")

# Every DCS target from here on. A UBSan finding stops the run as ASan's do (libFuzzer then
# saves the input), instead of printing and going on. libstdc++'s assertions turn what neither
# sanitizer sees into a crash too: an empty std::optional dereferenced, an index out of a
# vector's bounds (an allocation may be larger than its size).
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fno-omit-frame-pointer -D_GLIBCXX_ASSERTIONS)
add_link_options(-fsanitize=address,undefined)

set(DCS_LIBRARY_FOLDER_OPTIONS EXCLUDE_FROM_ALL)
