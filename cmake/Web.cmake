# The browser build (Emscripten, WebGL 1), included by CMakeLists.txt after the base, gl, scene, core and viewer
# libraries are defined: the same libraries and shaders, plus the WebGL front-end (platform/WebCanvas) and the
# exported C API (apps/obscura_web.cpp) that web/obscura.js wraps. The demo page is assembled in <build>/site:
#   obscura-core.js + obscura-core.wasm   the module (an ES module factory: createObscuraCore)
#   index.html, app.js, obscura.js, gltf-decoders.js, style.css   copied from web/
#   decoders/   the npm Draco and meshopt decoders (web/package.json)
# Build with tools/build-web.sh.

# The core reports bad input with exceptions (InputError): catching them needs exception support on every object
# file and at link time (Emscripten's default only lets them propagate to an abort).
foreach(library obscura_base obscura_gl obscura_scene obscura_core obscura_viewer)
  target_compile_options(${library} PUBLIC -fexceptions)
endforeach()

set(OBSCURA_SITE_DIR "${CMAKE_BINARY_DIR}/site")

add_executable(obscura-web src/apps/obscura_web.cpp src/platform/WebCanvas.cpp)
target_link_libraries(obscura-web PRIVATE obscura_viewer obscura_warnings)
set_target_properties(obscura-web PROPERTIES OUTPUT_NAME obscura-core SUFFIX ".js"
                                             RUNTIME_OUTPUT_DIRECTORY "${OBSCURA_SITE_DIR}")
target_link_options(obscura-web PRIVATE
  -fexceptions
  # WebGL 1 and nothing newer: no WebGL 2 entry point is even linked.
  -sMIN_WEBGL_VERSION=1 -sMAX_WEBGL_VERSION=1
  -sENVIRONMENT=web
  -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=createObscuraCore
  # Scenes of tens of megabytes arrive at run time.
  -sALLOW_MEMORY_GROWTH=1
  # No main(): web/obscura.js starts the module with obscura_create() once the canvas is known.
  --no-entry
  -sEXPORTED_FUNCTIONS=_malloc,_free
  -sEXPORTED_RUNTIME_METHODS=ccall,UTF8ToString)

# The page's static files, copied whenever they change.
set(web_files index.html app.js obscura.js gltf-decoders.js style.css)
set(site_files "")
foreach(file IN LISTS web_files)
  add_custom_command(OUTPUT "${OBSCURA_SITE_DIR}/${file}"
                     COMMAND "${CMAKE_COMMAND}" -E copy "${CMAKE_SOURCE_DIR}/web/${file}" "${OBSCURA_SITE_DIR}/${file}"
                     DEPENDS "${CMAKE_SOURCE_DIR}/web/${file}")
  list(APPEND site_files "${OBSCURA_SITE_DIR}/${file}")
endforeach()
# The npm glTF geometry decoders (web/package.json: draco3d, meshoptimizer), which tools/build-web.sh installs into
# web/node_modules, into the site's decoders/ folder (web/gltf-decoders.js loads them from there).
set(decoder_files "draco3d/draco_decoder_nodejs.js" "draco3d/draco_decoder.wasm"
                  "meshoptimizer/meshopt_decoder.module.js")
foreach(file IN LISTS decoder_files)
  get_filename_component(name "${file}" NAME)
  set(source "${CMAKE_SOURCE_DIR}/web/node_modules/${file}")
  if(NOT EXISTS "${source}")
    message(FATAL_ERROR "Missing ${source}: run npm ci in web/ (tools/build-web.sh does)")
  endif()
  add_custom_command(OUTPUT "${OBSCURA_SITE_DIR}/decoders/${name}"
                     COMMAND "${CMAKE_COMMAND}" -E copy "${source}" "${OBSCURA_SITE_DIR}/decoders/${name}"
                     DEPENDS "${source}")
  list(APPEND site_files "${OBSCURA_SITE_DIR}/decoders/${name}")
endforeach()
add_custom_target(obscura-site ALL DEPENDS ${site_files})
add_dependencies(obscura-site obscura-web)
