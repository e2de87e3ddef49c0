# The layering rule the build enforces (docs/architecture.md §1). Every DCS library (and
# program) has a layer, declared once in cmake/layers.cmake with dcs_layer(); it may link DCS
# libraries of lower layers only, and gRPC, libtorch or SQLite (the coordinator's store) only
# where its layer allows them.
#
# dcs_check_layers(), called after every target exists, walks each library's whole link closure
# (its own libraries, theirs, and so on, third-party ones included) and stops the configure
# step naming the library, what it must not link, and the chain through which it does. It also
# writes ${PROJECT_BINARY_DIR}/layers_for_test.cmake (each library's folder and layer), which
# cmake/check_includes.cmake reads to hold every file's #include lines to the same rule.

# dcs_layer(<target> <rank> [GRPC] [TORCH] [SQLITE]): the library or program <target> sits at
# layer <rank> (0 is the bottom) and may link gRPC, libtorch or SQLite only if marked so.
function(dcs_layer library rank)
  cmake_parse_arguments(ARG "GRPC;TORCH;SQLITE" "" "" ${ARGN})
  set_property(GLOBAL APPEND PROPERTY DCS_LAYERED_LIBRARIES ${library})
  set_property(GLOBAL PROPERTY DCS_LAYER_RANK_${library} ${rank})
  set_property(GLOBAL PROPERTY DCS_LAYER_GRPC_${library} ${ARG_GRPC})
  set_property(GLOBAL PROPERTY DCS_LAYER_TORCH_${library} ${ARG_TORCH})
  set_property(GLOBAL PROPERTY DCS_LAYER_SQLITE_${library} ${ARG_SQLITE})
endfunction()

# The third-party family `item` (a target or a file) belongs to: "gRPC", "libtorch", "SQLite"
# or "".
function(_dcs_family item out)
  set(family "")
  if(item MATCHES "^gRPC::" OR item MATCHES "/libgrpc[^/]*$")
    set(family "gRPC")
  elseif(item MATCHES "^(torch|torch_library|torch_cpu|c10)$" OR
         item MATCHES "/lib(torch|c10)[^/]*$")
    set(family "libtorch")
  elseif(item MATCHES "^(SQLiteCpp|SQLite::SQLite3|sqlite3)$" OR
         item MATCHES "/lib(sqlite3|SQLiteCpp)[^/]*$")
    set(family "SQLite")
  endif()
  set(${out} "${family}" PARENT_SCOPE)
endfunction()

# The libraries `target` links directly, with $<LINK_ONLY:...> unwrapped and other generator
# expressions left out.
function(_dcs_direct_links target out)
  set(items)
  get_target_property(imported ${target} IMPORTED)
  foreach(property INTERFACE_LINK_LIBRARIES LINK_LIBRARIES)
    if(property STREQUAL "LINK_LIBRARIES" AND imported)
      continue()
    endif()
    get_target_property(links ${target} ${property})
    if(links)
      list(APPEND items ${links})
    endif()
  endforeach()
  set(result)
  foreach(item ${items})
    if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(item "${CMAKE_MATCH_1}")
    endif()
    if(NOT item MATCHES "\\$<" AND NOT item STREQUAL "")
      list(APPEND result "${item}")
    endif()
  endforeach()
  list(REMOVE_DUPLICATES result)
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# Checks `library`'s link closure. `chain` is how it was reached ("dcs_env -> dcs_proto").
function(_dcs_check_closure library target chain visited_var)
  set(visited ${${visited_var}})
  _dcs_direct_links(${target} links)
  get_property(rank GLOBAL PROPERTY DCS_LAYER_RANK_${library})
  get_property(grpc_allowed GLOBAL PROPERTY DCS_LAYER_GRPC_${library})
  get_property(torch_allowed GLOBAL PROPERTY DCS_LAYER_TORCH_${library})
  get_property(sqlite_allowed GLOBAL PROPERTY DCS_LAYER_SQLITE_${library})
  get_property(layered GLOBAL PROPERTY DCS_LAYERED_LIBRARIES)
  foreach(item ${links})
    if(item IN_LIST visited)
      continue()
    endif()
    list(APPEND visited ${item})
    set(path "${chain} -> ${item}")
    if(item IN_LIST layered)
      get_property(item_rank GLOBAL PROPERTY DCS_LAYER_RANK_${item})
      if(NOT item_rank LESS rank)
        message(FATAL_ERROR "Layering: ${library} (layer ${rank}) links ${item} (layer "
                            "${item_rank}), which is not below it: ${path}. A library links "
                            "only lower layers (cmake/layers.cmake, docs/architecture.md).")
      endif()
    endif()
    _dcs_family("${item}" family)
    if((family STREQUAL "gRPC" AND NOT grpc_allowed) OR
       (family STREQUAL "libtorch" AND NOT torch_allowed) OR
       (family STREQUAL "SQLite" AND NOT sqlite_allowed))
      set(what "${family}")
      if(family STREQUAL "SQLite")  # only the coordinator's store keeps records in it
        set(what "SQLite (the coordinator's store)")
      endif()
      message(FATAL_ERROR "Layering: ${library} must not link ${what}, but does: ${path}. "
                          "Only the layers marked ${family} in cmake/layers.cmake may "
                          "(docs/architecture.md).")
    endif()
    if(TARGET ${item})
      _dcs_check_closure(${library} ${item} "${path}" visited)
    endif()
  endforeach()
  set(${visited_var} ${visited} PARENT_SCOPE)
endfunction()

function(dcs_check_layers)
  get_property(layered GLOBAL PROPERTY DCS_LAYERED_LIBRARIES)
  # Every DCS library has a layer: a new one cannot slip past the rule.
  get_property(libraries GLOBAL PROPERTY DCS_LIBRARIES)
  foreach(library ${libraries})
    if(NOT library IN_LIST layered)
      message(FATAL_ERROR "Layering: ${library} has no layer; give it one in "
                          "cmake/layers.cmake.")
    endif()
  endforeach()
  set(for_test
      "# Generated by dcs_check_layers (cmake/layering.cmake); read by check_includes.cmake.\n")
  foreach(library ${layered})
    if(NOT TARGET ${library})
      message(FATAL_ERROR "Layering: cmake/layers.cmake names ${library}, which is no target.")
    endif()
    set(visited)
    _dcs_check_closure(${library} ${library} "${library}" visited)
    get_property(rank GLOBAL PROPERTY DCS_LAYER_RANK_${library})
    get_property(grpc GLOBAL PROPERTY DCS_LAYER_GRPC_${library})
    get_property(torch GLOBAL PROPERTY DCS_LAYER_TORCH_${library})
    get_property(sqlite GLOBAL PROPERTY DCS_LAYER_SQLITE_${library})
    # The folder of a library's hand-written sources (none for generated-only libraries); the
    # include check holds a folder to its library's layer (programs' mains sit in services/).
    get_target_property(type ${library} TYPE)
    if(NOT type STREQUAL "STATIC_LIBRARY")
      continue()
    endif()
    get_target_property(sources ${library} SOURCES)
    get_target_property(source_dir ${library} SOURCE_DIR)
    set(folder "")
    foreach(source ${sources})
      if(source MATCHES "\\.(cc|h)$" AND NOT source MATCHES "\\.pb\\.")
        get_filename_component(file "${source}" ABSOLUTE BASE_DIR "${source_dir}")
        get_filename_component(directory "${file}" DIRECTORY)
        file(RELATIVE_PATH folder "${PROJECT_SOURCE_DIR}" "${directory}")
      endif()
    endforeach()
    string(APPEND for_test
           "dcs_layer_for_test(${library} \"${folder}\" ${rank} \"${grpc}\" \"${torch}\" "
           "\"${sqlite}\")\n")
  endforeach()
  file(WRITE "${PROJECT_BINARY_DIR}/layers_for_test.cmake" "${for_test}")
endfunction()
