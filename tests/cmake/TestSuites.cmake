# ctest entries for a GoogleTest binary: one per test suite (one process per suite, so the fixtures a suite shares,
# the context, the Renderer and the sky's prefiltered environment are made once for it rather than once per test),
# or one per test with PER_TEST (binaries whose tests each run other processes, where a suite would run for minutes).
# The suites are listed after the binary is linked (tests/cmake/DiscoverSuites.cmake), so a new TEST() needs no
# CMake change. Every entry carries LABELS, plus "slow" for the suites or tests named in SLOW; its timeout is
# OBSCURA_TEST_TIMEOUT (120 s), or OBSCURA_SLOW_TEST_TIMEOUT (600 s) for slow ones, both times
# OBSCURA_TEST_TIMEOUT_SCALE (the sanitized tree's tests run several times slower).
#   obscura_add_gtest_suites(<target> PREFIX <name prefix> LABELS <label>... [SLOW <suite>...] [PER_TEST]
#                            [ENVIRONMENT <VAR=value>...] [RESOURCE_LOCK <name>])
set(OBSCURA_TEST_TIMEOUT 120 CACHE STRING "Timeout in seconds of a ctest entry of GoogleTest tests")
set(OBSCURA_SLOW_TEST_TIMEOUT 600 CACHE STRING "Timeout in seconds of a ctest entry labelled slow")
set(OBSCURA_TEST_TIMEOUT_SCALE 1 CACHE STRING "Factor on every test timeout (the sanitized tree sets 4)")
set(OBSCURA_TEST_RESULTS "${CMAKE_BINARY_DIR}/test-results"
    CACHE PATH "Where each GoogleTest entry writes its JSON report (tools/test-report.py reads them)")
# The prefiltered sky and environments, computed once per build rather than once per process
# (src/environment/PrefilterCache.h); every GoogleTest entry and the tools its tests run read and fill it.
set(OBSCURA_TEST_PREFILTER_CACHE "${CMAKE_BINARY_DIR}/test-cache"
    CACHE PATH "Where test processes keep prefiltered environments (empty: each process prefilters its own)")

function(obscura_add_gtest_suites target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "PER_TEST" "PREFIX;RESOURCE_LOCK" "LABELS;SLOW;ENVIRONMENT")
  math(EXPR timeout "${OBSCURA_TEST_TIMEOUT} * ${OBSCURA_TEST_TIMEOUT_SCALE}")
  math(EXPR slow_timeout "${OBSCURA_SLOW_TEST_TIMEOUT} * ${OBSCURA_TEST_TIMEOUT_SCALE}")
  string(MAKE_C_IDENTIFIER "${arg_PREFIX}" id)
  set(base "${CMAKE_CURRENT_BINARY_DIR}/${target}_${id}")
  set(per_test OFF)
  if(arg_PER_TEST)
    set(per_test ON)
  endif()
  if(OBSCURA_TEST_PREFILTER_CACHE)
    list(APPEND arg_ENVIRONMENT "OBSCURA_PREFILTER_CACHE=${OBSCURA_TEST_PREFILTER_CACHE}")
  endif()
  set(config "")
  foreach(variable IN ITEMS PREFIX LABELS SLOW ENVIRONMENT RESOURCE_LOCK)
    string(APPEND config "set(${variable} [==[${arg_${variable}}]==])\n")
  endforeach()
  string(APPEND config "set(OUTPUT [==[${base}_tests.cmake]==])\nset(PER_TEST ${per_test})\n"
                       "set(TIMEOUT ${timeout})\nset(SLOW_TIMEOUT ${slow_timeout})\n"
                       "set(RESULTS_DIR [==[${OBSCURA_TEST_RESULTS}]==])\n")
  # Written only when it changes; the binary relinks then, and its entries are listed again.
  file(CONFIGURE OUTPUT "${base}_config.cmake" CONTENT "${config}" @ONLY)
  set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS "${base}_config.cmake")
  add_custom_command(TARGET ${target} POST_BUILD
    COMMAND "${CMAKE_COMMAND}" -D "TEST_EXECUTABLE=$<TARGET_FILE:${target}>" -D "CONFIG=${base}_config.cmake"
            -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/DiscoverSuites.cmake"
    VERBATIM)
  file(WRITE "${base}_include.cmake"
       "if(EXISTS [==[${base}_tests.cmake]==])\n  include([==[${base}_tests.cmake]==])\nelse()\n"
       "  add_test([==[${arg_PREFIX}NOT_BUILT]==] [==[${arg_PREFIX}NOT_BUILT]==])\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${base}_include.cmake")
endfunction()
