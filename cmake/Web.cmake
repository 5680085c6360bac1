# The browser build (Emscripten, WebGL 1), included by CMakeLists.txt after the layer libraries (base .. renderer) and
# the viewer library are defined: the same libraries and shaders, plus the WebGL front-end (platform/WebCanvas) and the
# exported C API (apps/obscura_web.cpp) that web/obscura.js wraps. The demo page is assembled in <build>/site:
#   obscura-core.js + obscura-core.wasm   the module (an ES module factory: createObscuraCore)
#   index.html, app.js, obscura.js, gltf-decoders.js, style.css   copied from web/
#   decoders/   the npm Draco and meshopt decoders (web/package.json)
# Build with tools/build-web.sh.

# The core reports bad input with exceptions (InputError): catching them needs exception support on every object
# file and at link time (Emscripten's default only lets them propagate to an abort). WebAssembly's own exception
# handling (-fwasm-exceptions), not Emscripten's JavaScript one (-fexceptions), which wraps every call that may throw
# from a frame with destructors in a JavaScript trampoline (invoke_*): about a fifth of the render call's time on the
# page (docs/benchmarks.md, "Host time"). It needs Chrome 95, Firefox 100, Safari 15.2 or newer; Debian's emscripten
# ships the libraries it links (libc++-except, libc++abi-except, libunwind-except), nothing is built into its cache.
foreach(library obscura_base obscura_encoding obscura_gl obscura_meshopt_simplifier obscura_scene obscura_gpu
                obscura_environment obscura_frame obscura_effects obscura_renderer obscura_viewer)
  target_compile_options(${library} PUBLIC -fwasm-exceptions)
endforeach()

set(OBSCURA_SITE_DIR "${CMAKE_BINARY_DIR}/site")

# The page's API (obscura_web.cpp) and the public C++ API on the page's own WebGL context (obscura_web_geometry.cpp:
# AO on the page's geometry, web/obscura.js createAmbientOcclusion).
add_executable(obscura-web src/apps/obscura_web.cpp src/platform/WebCanvas.cpp src/apps/obscura_web_geometry.cpp
                           src/api/Renderer.cpp)
target_include_directories(obscura-web PRIVATE include "${CMAKE_BINARY_DIR}/include")
target_link_libraries(obscura-web PRIVATE obscura_viewer obscura_warnings)
set_target_properties(obscura-web PROPERTIES OUTPUT_NAME obscura-core SUFFIX ".js"
                                             RUNTIME_OUTPUT_DIRECTORY "${OBSCURA_SITE_DIR}")
target_link_options(obscura-web PRIVATE
  -fwasm-exceptions
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

# The npm package (obscura-webgl): the module, obscura.js, its TypeScript declarations, the glTF geometry decoders,
# the public GLSL chunk, a README and the license, with package.json at the project's version. `npm pack build-web/npm` makes the tarball
# (tests/npm-package does, and installs it into a scratch project).
set(OBSCURA_NPM_DIR "${CMAKE_BINARY_DIR}/npm")
configure_file(web/package/package.json.in "${OBSCURA_NPM_DIR}/package.json" @ONLY)
set(npm_sources
  "${CMAKE_SOURCE_DIR}/web/obscura.js" "${CMAKE_SOURCE_DIR}/web/gltf-decoders.js"
  "${CMAKE_SOURCE_DIR}/web/package/obscura.d.ts"
  "${CMAKE_SOURCE_DIR}/web/package/README.md" "${CMAKE_SOURCE_DIR}/LICENSE"
  "${CMAKE_SOURCE_DIR}/shaders_es2/lib/obscura_gbuffer.glsl")
set(npm_files "")
foreach(source IN LISTS npm_sources)
  get_filename_component(name "${source}" NAME)
  add_custom_command(OUTPUT "${OBSCURA_NPM_DIR}/${name}"
                     COMMAND "${CMAKE_COMMAND}" -E copy "${source}" "${OBSCURA_NPM_DIR}/${name}" DEPENDS "${source}")
  list(APPEND npm_files "${OBSCURA_NPM_DIR}/${name}")
endforeach()
add_custom_command(OUTPUT "${OBSCURA_NPM_DIR}/obscura-core.js" "${OBSCURA_NPM_DIR}/obscura-core.wasm"
                   COMMAND "${CMAKE_COMMAND}" -E copy "${OBSCURA_SITE_DIR}/obscura-core.js"
                           "${OBSCURA_SITE_DIR}/obscura-core.wasm" "${OBSCURA_NPM_DIR}"
                   DEPENDS obscura-web)
# The glTF geometry decoders too, in decoders/ as on the site: obscura.js imports gltf-decoders.js, which fetches
# them from there the first time a compressed file needs them.
foreach(file IN LISTS decoder_files)
  get_filename_component(name "${file}" NAME)
  add_custom_command(OUTPUT "${OBSCURA_NPM_DIR}/decoders/${name}"
                     COMMAND "${CMAKE_COMMAND}" -E copy "${CMAKE_SOURCE_DIR}/web/node_modules/${file}"
                             "${OBSCURA_NPM_DIR}/decoders/${name}"
                     DEPENDS "${CMAKE_SOURCE_DIR}/web/node_modules/${file}")
  list(APPEND npm_files "${OBSCURA_NPM_DIR}/decoders/${name}")
endforeach()
add_custom_target(obscura-npm ALL DEPENDS ${npm_files} "${OBSCURA_NPM_DIR}/obscura-core.js"
                                          "${OBSCURA_NPM_DIR}/obscura-core.wasm")
