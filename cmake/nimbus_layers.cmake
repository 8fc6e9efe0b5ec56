# Build-time enforcement of the layer boundary (docs/architecture.md).

# Fails the configure step when any of TARGETS links any of FORBIDDEN, directly or through the
# libraries it links (a CPU layer that would need OpenGL or EGL to link).
function(nimbus_forbid_links)
  cmake_parse_arguments(arg "" "" "TARGETS;FORBIDDEN" ${ARGN})
  foreach(target IN LISTS arg_TARGETS)
    set(seen "")
    set(queue ${target})
    while(queue)
      list(POP_FRONT queue current)
      if(current IN_LIST seen OR NOT TARGET ${current})
        continue()
      endif()
      list(APPEND seen ${current})
      get_target_property(aliased ${current} ALIASED_TARGET)
      if(aliased)
        list(APPEND queue ${aliased})
      endif()
      foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
        get_target_property(links ${current} ${property})
        if(NOT links)
          continue()
        endif()
        foreach(link IN LISTS links)
          string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" link "${link}")
          if(link IN_LIST arg_FORBIDDEN)
            message(FATAL_ERROR "layer boundary: ${target} links ${link} (through ${current}); "
                                "the CPU layers must build and link without OpenGL or EGL")
          endif()
          list(APPEND queue ${link})
        endforeach()
      endforeach()
    endwhile()
  endforeach()
endfunction()

# Runs cmake/check_layers.cmake over the sources before any of the given targets compiles, and
# again whenever a source changes: an include that crosses a layer fails the build.
function(nimbus_check_includes)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/base/*.[ch]pp ${PROJECT_SOURCE_DIR}/noise/*.[ch]pp
       ${PROJECT_SOURCE_DIR}/volume/*.[ch]pp ${PROJECT_SOURCE_DIR}/render/*.[ch]pp)
  set(stamp ${CMAKE_BINARY_DIR}/nimbus_layers.stamp)
  add_custom_command(
    OUTPUT ${stamp}
    COMMAND ${CMAKE_COMMAND} -DROOT=${PROJECT_SOURCE_DIR} -DSTAMP=${stamp} -P ${PROJECT_SOURCE_DIR}/cmake/check_layers.cmake
    DEPENDS ${sources} ${PROJECT_SOURCE_DIR}/cmake/check_layers.cmake
    COMMENT "Checking the layer boundary (cmake/check_layers.cmake)"
    VERBATIM)
  add_custom_target(nimbus_layers DEPENDS ${stamp})
  foreach(target IN LISTS ARGN)
    add_dependencies(${target} nimbus_layers)
  endforeach()
endfunction()
