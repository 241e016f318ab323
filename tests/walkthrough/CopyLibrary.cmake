# walkthrough_copy_library(<copy> <original> [REPLACE <library> <replacement> ...])
# A STATIC library built from <original>'s unchanged sources with its include directories, compile
# definitions, options and features, linking what <original> links, each <library> named after
# REPLACE swapped for its <replacement>. It reads the original target's properties, so a source
# added to a backend is picked up here without editing this file; a link to a project library that
# is not replaced stops the configuration (it would pull the real effect into the copy).
function(walkthrough_copy_library copy original)
  cmake_parse_arguments(ARG "" "" "REPLACE" ${ARGN})
  get_target_property(dir ${original} SOURCE_DIR)
  get_target_property(sources ${original} SOURCES)
  set(absolute "")
  foreach(s IN LISTS sources)
    if(NOT IS_ABSOLUTE "${s}")
      set(s "${dir}/${s}")
    endif()
    list(APPEND absolute "${s}")
  endforeach()
  add_library(${copy} STATIC ${absolute})

  foreach(prop INCLUDE_DIRECTORIES INTERFACE_INCLUDE_DIRECTORIES COMPILE_DEFINITIONS COMPILE_OPTIONS
               COMPILE_FEATURES INTERFACE_COMPILE_FEATURES INTERFACE_COMPILE_DEFINITIONS)
    get_target_property(value ${original} ${prop})
    if(value)
      set_property(TARGET ${copy} PROPERTY ${prop} "${value}")
    endif()
  endforeach()

  foreach(prop LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
    get_target_property(value ${original} ${prop})
    if(NOT value)
      continue()
    endif()
    set(replaced "")
    foreach(item IN LISTS value)
      set(pairs ${ARG_REPLACE})
      while(pairs)
        list(POP_FRONT pairs from to)
        if(item STREQUAL from)
          set(item "${to}")
        else()  # inside a generator expression such as $<LINK_ONLY:sao::core>
          string(REPLACE ":${from}>" ":${to}>" item "${item}")
        endif()
      endwhile()
      list(APPEND replaced "${item}")
    endforeach()
    set(value "${replaced}")
    string(REGEX MATCH "(^|[;<>:,])(sao::[A-Za-z_]+|sao_[a-z_]+)" leftover "${value}")
    if(leftover)
      message(FATAL_ERROR "walkthrough_copy_library(${copy}): ${original} links '${CMAKE_MATCH_2}', "
                          "which has no REPLACE entry; add its walkthrough copy")
    endif()
    set_property(TARGET ${copy} PROPERTY ${prop} "${value}")
  endforeach()
endfunction()
