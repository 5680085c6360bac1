# The layers of src/ point down only (docs/architecture.md, "The tree"): every `#include "dir/..."` of a file in one
# layer must name a layer below it or its own. An effect (src/effects/NAME/) includes no other effect: what effects
# share lives in frame/ (the plan, the pass plumbing, the tile passes), encoding/ (the RGBA8 encodings and their CPU
# mirrors) or shaders_es2/lib/.
#
# Run at build time (the check_layers target, part of ALL), so an include against the direction fails the build:
#   cmake -DSOURCE_DIR=<src> -DSTAMP=<file> -P CheckLayers.cmake
cmake_minimum_required(VERSION 3.25)

# Each layer, and the layers its files may include besides their own. Third-party and system headers use <...>.
set(below_base "")
set(below_encoding base)
set(below_gl base)
set(below_scene base)
set(below_gpu base encoding gl scene)
set(below_environment base encoding gl)
set(below_frame base encoding gl scene gpu environment)
set(below_effects base encoding gl scene gpu environment frame)
set(below_renderer base encoding gl scene gpu environment frame effects)
set(below_reference base encoding scene)
set(below_metrics base scene)
set(below_platform base encoding gl scene gpu environment frame effects renderer)
set(below_api base encoding gl scene gpu environment frame effects renderer platform obscura)
set(below_apps base encoding gl scene gpu environment frame effects renderer platform api reference metrics obscura)

# Effect-to-effect includes still to be removed, each with its reason. Empty this list, do not grow it.
set(allowed_effect_includes)

file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/*.h" "${SOURCE_DIR}/*.cpp" "${SOURCE_DIR}/*.inc")
set(violations "")
foreach(file IN LISTS sources)
  string(REGEX MATCH "^[a-z_]+" layer "${file}")
  if(NOT DEFINED below_${layer})
    list(APPEND violations "${file}: src/${layer}/ is not a layer of docs/architecture.md")
    continue()
  endif()
  set(effect "")
  if(layer STREQUAL "effects")
    string(REGEX REPLACE "^effects/([a-z_]+)/.*" "\\1" effect "${file}")
  endif()
  file(STRINGS "${SOURCE_DIR}/${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]+\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" included "${line}")
    if(NOT included MATCHES "/")
      continue()  # a file beside it
    endif()
    string(REGEX MATCH "^[a-z_]+" target "${included}")
    if(target STREQUAL layer)
      if(layer STREQUAL "effects")
        string(REGEX REPLACE "^effects/([a-z_]+)/.*" "\\1" other "${included}")
        if(NOT other STREQUAL effect AND NOT "${effect}->${other}" IN_LIST allowed_effect_includes)
          list(APPEND violations "${file}: includes ${included}, another effect's (an effect never includes another)")
        endif()
      endif()
      continue()
    endif()
    if(NOT target IN_LIST below_${layer})
      list(APPEND violations "${file}: includes ${included}, but ${layer}/ may include only ${below_${layer}}")
    endif()
  endforeach()
endforeach()

if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "Includes against the layers' direction (cmake/CheckLayers.cmake):\n  ${text}")
endif()
if(STAMP)
  get_filename_component(stamp_dir "${STAMP}" DIRECTORY)
  file(MAKE_DIRECTORY "${stamp_dir}")
  file(TOUCH "${STAMP}")
endif()
