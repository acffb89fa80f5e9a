# Sanitized builds (issue 11): NONSMOOTH_SIM_SANITIZE selects the runtime checks compiled into
# every target of the project (the core, the loader, the node, simulate, the benchmarks and every
# test executable; system libraries such as roscpp are not instrumented):
#
#   ""        none (default; the Release build of scripts/build and scripts/test)
#   address   AddressSanitizer (with LeakSanitizer) and UndefinedBehaviorSanitizer; any undefined
#             behaviour report is fatal (-fno-sanitize-recover=undefined)
#   thread    ThreadSanitizer
#
# -g1 (line tables) is added either way so that reports carry file:line in any build type; full
# -g made the objects seven times larger and the compile 30 % slower, for local variables that no
# report prints. scripts/test
# --sanitize and --tsan configure it, set the runtime options and suppressions
# (test/sanitizers/) and run the whole suite; docs/testing.md. Included from CMakeLists.txt right
# after the warning options, before any target is defined (add_compile_options and
# add_link_options apply to the targets defined after them).
set(NONSMOOTH_SIM_SANITIZE "" CACHE STRING
    "Sanitizers for every target: empty (none), address (ASan + LSan + UBSan) or thread (TSan)")
set_property(CACHE NONSMOOTH_SIM_SANITIZE PROPERTY STRINGS "" address thread)

if(NONSMOOTH_SIM_SANITIZE STREQUAL "")
  set(NONSMOOTH_SIM_SANITIZER_FLAGS "")
elseif(NONSMOOTH_SIM_SANITIZE STREQUAL "address")
  set(NONSMOOTH_SIM_SANITIZER_FLAGS
      -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
elseif(NONSMOOTH_SIM_SANITIZE STREQUAL "thread")
  set(NONSMOOTH_SIM_SANITIZER_FLAGS -fsanitize=thread)
else()
  message(FATAL_ERROR "NONSMOOTH_SIM_SANITIZE='${NONSMOOTH_SIM_SANITIZE}': "
                      "use an empty value, address or thread")
endif()

if(NONSMOOTH_SIM_SANITIZER_FLAGS)
  message(STATUS "nonsmooth_sim: sanitizers ${NONSMOOTH_SIM_SANITIZE}: "
                 "${NONSMOOTH_SIM_SANITIZER_FLAGS}")
  add_compile_options(${NONSMOOTH_SIM_SANITIZER_FLAGS} -g1)
  add_link_options(${NONSMOOTH_SIM_SANITIZER_FLAGS})
endif()
