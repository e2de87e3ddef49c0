# Holds every #include of every DCS library folder to the layering rule (cmake/layering.cmake):
# a file includes headers of its own library and of lower layers only, and gRPC's, libtorch's
# or SQLite's headers (or those of a library that links SQLite: the coordinator's store) only if
# its layer may link them. The link check sees what a library links; this sees
# what its code uses, file by file, the moment a line is added (a test, so no reconfigure is
# needed).
#
#   cmake -DSOURCE_ROOT=<tree to check> -DLAYERS=<build>/layers_for_test.cmake \
#         -P cmake/check_includes.cmake
#
# Prints one line per offending include ("env/x.cc:12: includes learner/y.h (layer 4) ...")
# and fails if there is any.

cmake_minimum_required(VERSION 3.25)
if(NOT SOURCE_ROOT OR NOT LAYERS)
  message(FATAL_ERROR "usage: cmake -DSOURCE_ROOT=<dir> -DLAYERS=<file> -P check_includes.cmake")
endif()

# Reads the table written by dcs_check_layers.
set(libraries)
function(dcs_layer_for_test library folder rank grpc torch sqlite)
  set_property(GLOBAL APPEND PROPERTY LIBRARIES ${library})
  set_property(GLOBAL PROPERTY FOLDER_${library} "${folder}")
  set_property(GLOBAL PROPERTY RANK_${library} ${rank})
  set_property(GLOBAL PROPERTY GRPC_${library} ${grpc})
  set_property(GLOBAL PROPERTY TORCH_${library} ${torch})
  set_property(GLOBAL PROPERTY SQLITE_${library} ${sqlite})
endfunction()
include("${LAYERS}")
get_property(libraries GLOBAL PROPERTY LIBRARIES)

# The DCS library whose header `include` (as written between quotes) is, or "".
function(library_of include out)
  set(found "")
  if(include MATCHES "^(dcs|grpc)/.*\\.grpc\\.pb\\.h$")
    set(found dcs_proto_grpc)
  elseif(include MATCHES "^(dcs|grpc)/")
    set(found dcs_proto)
  else()
    set(longest 0)
    foreach(library ${libraries})
      get_property(folder GLOBAL PROPERTY FOLDER_${library})
      string(LENGTH "${folder}" length)
      if(NOT folder STREQUAL "" AND include MATCHES "^${folder}/[^/]+$" AND length GREATER longest)
        set(found ${library})
        set(longest ${length})
      endif()
    endforeach()
  endif()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

set(violations)
foreach(library ${libraries})
  get_property(folder GLOBAL PROPERTY FOLDER_${library})
  if(folder STREQUAL "")
    continue()
  endif()
  get_property(rank GLOBAL PROPERTY RANK_${library})
  get_property(grpc GLOBAL PROPERTY GRPC_${library})
  get_property(torch GLOBAL PROPERTY TORCH_${library})
  get_property(sqlite GLOBAL PROPERTY SQLITE_${library})
  file(GLOB files "${SOURCE_ROOT}/${folder}/*.h" "${SOURCE_ROOT}/${folder}/*.cc")
  foreach(file ${files})
    file(RELATIVE_PATH name "${SOURCE_ROOT}" "${file}")
    file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${lines})
      if(NOT line MATCHES "#[ \t]*include[ \t]*[\"<]([^\">]+)[\">]")
        continue()
      endif()
      set(include "${CMAKE_MATCH_1}")
      set(problem "")
      if(include MATCHES "^(grpcpp|grpc\\+\\+|grpc)/" AND NOT include MATCHES "\\.pb\\.h$" OR
         include MATCHES "\\.grpc\\.pb\\.h$")
        if(NOT grpc)
          set(problem "a gRPC header, and ${library} must not use gRPC")
        endif()
      elseif(include MATCHES "^(torch|ATen|c10)/")
        if(NOT torch)
          set(problem "a libtorch header, and ${library} must not use libtorch")
        endif()
      elseif(include MATCHES "^(SQLiteCpp/|sqlite3\\.h$)")
        if(NOT sqlite)
          set(problem "a SQLite header, and ${library} must not use the store")
        endif()
      elseif(include MATCHES "^tests/")
        set(problem "a test's header")
      endif()
      library_of("${include}" included)
      if(problem STREQUAL "" AND NOT "${included}" STREQUAL "" AND
         NOT "${included}" STREQUAL "${library}")
        get_property(included_rank GLOBAL PROPERTY RANK_${included})
        get_property(included_sqlite GLOBAL PROPERTY SQLITE_${included})
        if(NOT included_rank LESS rank)
          set(problem "of ${included} (layer ${included_rank}), not below ${library} "
                      "(layer ${rank})")
          string(CONCAT problem ${problem})
        elseif(included_sqlite AND NOT sqlite)
          set(problem "of ${included}, which links SQLite (the coordinator's store), and "
                      "${library} must not use the store")
          string(CONCAT problem ${problem})
        endif()
      endif()
      if(NOT problem STREQUAL "")
        list(APPEND violations "${name}: includes ${include}, ${problem}")
      endif()
    endforeach()
  endforeach()
endforeach()

if(violations)
  list(LENGTH violations count)
  string(REPLACE ";" "\n" listed "${violations}")
  message(FATAL_ERROR "${count} include(s) break the layering (cmake/layers.cmake, "
                      "docs/architecture.md):\n${listed}")
endif()
message(STATUS "every include respects the layers")
