# Header-only third-party libraries from Debian: GLM, tinygltf, nlohmann-json and stb.
#
# Only their own include folders are put on the compiler's path. For the WebAssembly build this matters: adding all
# of /usr/include would pull the host's libc headers into the wasm compile. So the headers are mirrored (as symbolic
# links) into one folder of the build tree, and that folder is the only one added, on every platform alike.
set(OBSCURA_THIRD_PARTY_ROOT "/usr/include" CACHE PATH "Where Debian's libglm-dev, libtinygltf-dev, nlohmann-json3-dev and libstb-dev put their headers")
set(_mirror "${CMAKE_BINARY_DIR}/third_party_include")
file(MAKE_DIRECTORY "${_mirror}")

set(_links
  "glm=${OBSCURA_THIRD_PARTY_ROOT}/glm"
  "nlohmann=${OBSCURA_THIRD_PARTY_ROOT}/nlohmann"
  "tiny_gltf.h=${OBSCURA_THIRD_PARTY_ROOT}/tiny_gltf.h"
  "stb_image.h=${OBSCURA_THIRD_PARTY_ROOT}/stb/stb_image.h"
  "stb_image_write.h=${OBSCURA_THIRD_PARTY_ROOT}/stb/stb_image_write.h"
  "stb_image_resize.h=${OBSCURA_THIRD_PARTY_ROOT}/stb/stb_image_resize.h")
foreach(link IN LISTS _links)
  string(REPLACE "=" ";" parts "${link}")
  list(GET parts 0 name)
  list(GET parts 1 target)
  if(NOT EXISTS "${target}")
    message(FATAL_ERROR "Missing ${target}: install libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev "
                        "(tools/install-deps.sh does).")
  endif()
  file(CREATE_LINK "${target}" "${_mirror}/${name}" SYMBOLIC)
endforeach()

add_library(obscura_third_party INTERFACE)
target_include_directories(obscura_third_party SYSTEM INTERFACE "${_mirror}")
# GLM: radians everywhere, depth range [-1, 1] as in OpenGL ES.
target_compile_definitions(obscura_third_party INTERFACE GLM_FORCE_RADIANS GLM_ENABLE_EXPERIMENTAL)
