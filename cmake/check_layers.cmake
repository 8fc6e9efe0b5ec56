# Checks the layer boundary of nimbus's sources (docs/architecture.md): every file under a
# module's folder may include only the nimbus headers of the modules below it, and only the GL
# layer and the GPU methods above it may include OpenGL, EGL or GLFW headers.
#   cmake -DROOT=<source tree> [-DSTAMP=<file to touch on success>] -P cmake/check_layers.cmake
# Exits with an error naming each offending file, line and include.
if(NOT ROOT)
  message(FATAL_ERROR "check_layers: pass -DROOT=<source tree>")
endif()

# folder | nimbus include prefixes it may use (comma-separated) | may it include GL headers
set(rules
  "base|nimbus/base/|no"
  "noise|nimbus/base/,nimbus/noise/|no"
  "volume|nimbus/base/,nimbus/noise/,nimbus/volume/|no"
  "render/core|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/|no"
  "render/media|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/|no"
  "render/scene|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/|no"
  "render/image|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/image/|no"
  "render/reference|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/reference/|no"
  "render/sky|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/reference/,nimbus/render/sky/|no"
  "render/gl|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/gl/|yes"
  "render/shafts|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/gl/,nimbus/render/shafts/|yes"
  "render/clouds|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/gl/,nimbus/render/clouds/|yes"
  "render/frame|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/image/,nimbus/render/reference/,nimbus/render/sky/,nimbus/render/gl/,nimbus/render/shafts/,nimbus/render/clouds/,nimbus/render/frame/|yes"
  "samples/app|nimbus/base/,nimbus/noise/,nimbus/volume/,nimbus/render/core/,nimbus/render/media/,nimbus/render/scene/,nimbus/render/image/,nimbus/render/reference/,nimbus/render/sky/,nimbus/app/|no"
)
set(gl_header_regex "^(epoxy|EGL|GL|GLES[0-9]*|GLFW|KHR)/")

set(errors "")
set(checked 0)
foreach(rule IN LISTS rules)
  string(REPLACE "|" ";" parts "${rule}")
  list(GET parts 0 folder)
  list(GET parts 1 allowed)
  string(REPLACE "," ";" allowed "${allowed}")
  list(GET parts 2 gl_ok)
  file(GLOB_RECURSE files "${ROOT}/${folder}/*.cpp" "${ROOT}/${folder}/*.hpp" "${ROOT}/${folder}/*.h")
  foreach(f IN LISTS files)
    math(EXPR checked "${checked} + 1")
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]")
    file(RELATIVE_PATH rel "${ROOT}" "${f}")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*[<\"]([^>\"]*)[>\"].*$" "\\1" header "${line}")
      if(header MATCHES "^nimbus/")
        set(ok FALSE)
        foreach(prefix IN LISTS allowed)
          string(FIND "${header}" "${prefix}" at)
          if(at EQUAL 0)
            set(ok TRUE)
          endif()
        endforeach()
        if(NOT ok)
          string(APPEND errors "  ${rel}: includes ${header}, above the ${folder} layer\n")
        endif()
      elseif(header MATCHES "${gl_header_regex}" AND NOT gl_ok STREQUAL "yes")
        string(APPEND errors "  ${rel}: includes ${header}, but ${folder} must build without OpenGL, EGL or GLFW\n")
      endif()
    endforeach()
  endforeach()
endforeach()

if(checked EQUAL 0)
  message(FATAL_ERROR "check_layers: no sources found under ${ROOT}")
endif()
if(errors)
  message(FATAL_ERROR "layer boundary broken (docs/architecture.md):\n${errors}")
endif()
if(STAMP)
  file(WRITE "${STAMP}" "${checked} files checked\n")
endif()
