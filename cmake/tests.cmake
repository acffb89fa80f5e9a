# Tests and benchmarks of everything but the ROS layer (whose tests are in cmake/ros.cmake).
# Included from CMakeLists.txt when CATKIN_ENABLE_TESTING (always on without ROS). Every
# test/<dir>/*_test.cpp is one GoogleTest executable, one ctest entry per TEST (cmake/gtests.cmake).
include(${PROJECT_SOURCE_DIR}/cmake/gtests.cmake)

nonsmooth_sim_add_gtests(DIR test/core LIBRARIES nonsmooth_sim_core)
# "scene_io.<Suite>.<Test>"
nonsmooth_sim_add_gtests(DIR test/scene_io PREFIX scene_io LIBRARIES nonsmooth_sim_scene_io
                         nonsmooth_sim_mesh nonsmooth_sim_collision_fcl)
nonsmooth_sim_add_gtests(DIR test/collision_fcl LIBRARIES nonsmooth_sim_collision_fcl)
# the world on its own: "world.<Suite>.<Test>"
nonsmooth_sim_add_gtests(DIR test/world PREFIX world LIBRARIES nonsmooth_sim_world
                         nonsmooth_sim_collision_fcl)
# An independent reference for bodies rolling without slipping (test/reference/rolling_reference.h:
# Eigen and Boost.Odeint only, nothing of the core), for tests that hold the integrators to it
# (#include "reference/rolling_reference.h"); its own checks are "reference.<Suite>.<Test>".
find_package(Boost 1.65 REQUIRED)  # header-only: odeint
add_library(nonsmooth_sim_rolling_reference STATIC EXCLUDE_FROM_ALL
  ${PROJECT_SOURCE_DIR}/test/reference/rolling_bodies.cpp
  ${PROJECT_SOURCE_DIR}/test/reference/rolling_reference.cpp
  ${PROJECT_SOURCE_DIR}/test/reference/rolling_lagrange.cpp)
target_include_directories(nonsmooth_sim_rolling_reference PUBLIC ${PROJECT_SOURCE_DIR}/test)
target_link_libraries(nonsmooth_sim_rolling_reference PUBLIC Eigen3::Eigen Boost::headers)
nonsmooth_sim_add_gtests(DIR test/reference PREFIX reference LIBRARIES nonsmooth_sim_rolling_reference)
# Physics of the shipped scenes (urdf/*.urdf + config/*.yaml through the loader, stepped by the
# core): "scenes.<Suite>.<Test>"; the derivations and numbers they check are in docs/scenes.md.
nonsmooth_sim_add_gtests(DIR test/scenes PREFIX scenes LIBRARIES nonsmooth_sim_scene_io
                         nonsmooth_sim_core nonsmooth_sim_rolling_reference)
# `simulate` through its command line: every test/simulate/<name>.py, run by Debian's python3
# with the executable and the source folder, 300 s at most.
function(nonsmooth_sim_add_simulate_test name)
  add_test(NAME ${name}
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/simulate/${name}.py
            $<TARGET_FILE:simulate> ${PROJECT_SOURCE_DIR})
  set_tests_properties(${name} PROPERTIES TIMEOUT 300)
endfunction()
# devices, FIFOs, oversize files and out of memory: one line and a documented exit code
# (docs/simulate.md, "Exit codes"); the sanitizer (if any) is passed on: a sanitizer's runtime
# cannot start under the test's address-space limit, so the out-of-memory case is skipped in
# sanitized builds
nonsmooth_sim_add_simulate_test(simulate_files_test)
set_tests_properties(simulate_files_test PROPERTIES
  ENVIRONMENT "NONSMOOTH_SIM_SANITIZE=${NONSMOOTH_SIM_SANITIZE}")
# a body that can no longer touch anything: warned once and listed in the summary
nonsmooth_sim_add_simulate_test(simulate_lost_bodies_test)
# --rolling-resistance: bad values refused, the rolling percussion in the CSV
nonsmooth_sim_add_simulate_test(simulate_rolling_resistance_test)
# --contacts-csv: a resting ball's weight, the Tippe-Top's spheres, one row per contact
nonsmooth_sim_add_simulate_test(simulate_contacts_csv_test)
# scripts/dev/mesh_tippe_top's URDFs: the mesh top inverts with the spheres
nonsmooth_sim_add_simulate_test(simulate_mesh_tippe_top_test)
# --schedule runs the documented example and each event has its effect in the CSV
nonsmooth_sim_add_simulate_test(simulate_schedule_test)

# ---------------------------------------------------------------------------------------------
# Benchmarks (Google Benchmark; timing lives here, never in tests). Run through scripts/dev/bench:
# the core's pieces, the shape pairs (closed forms next to FCL), one step of each shipped scene.
find_package(benchmark QUIET)
file(GLOB NONSMOOTH_SIM_BENCH_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/bench/*_bench.cpp)
if(benchmark_FOUND AND NONSMOOTH_SIM_BENCH_SOURCES)
  add_executable(nonsmooth_sim_bench EXCLUDE_FROM_ALL ${NONSMOOTH_SIM_BENCH_SOURCES})
  add_dependencies(tests nonsmooth_sim_bench)  # built with the tests, not installed
  target_link_libraries(nonsmooth_sim_bench PRIVATE nonsmooth_sim_core nonsmooth_sim_scene_io
    nonsmooth_sim_collision_fcl benchmark::benchmark benchmark::benchmark_main)
  set_target_properties(nonsmooth_sim_bench PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})
  target_compile_definitions(nonsmooth_sim_bench PRIVATE
    NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
endif()

# The Tippe-Top's step written for one body on the ground, from the core's pieces: the bound on
# what restructuring Simulator::Step for that case could gain (bench/one_body_bound.cpp,
# docs/performance.md). Each run checks that it took Simulator's steps bit for bit (exit 1 if
# not); run by hand, not a ctest.
add_executable(one_body_bound EXCLUDE_FROM_ALL ${PROJECT_SOURCE_DIR}/bench/one_body_bound.cpp)
add_dependencies(tests one_body_bound)
target_link_libraries(one_body_bound PRIVATE nonsmooth_sim_core)
set_target_properties(one_body_bound PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${NONSMOOTH_SIM_BIN_DIR})

# Every repository path named in the docs, build files and comments exists (no ROS needed).
add_test(NAME docs_paths_test
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/docs/paths_test.py)

# Every listing of the friction sets outside the code (comments in msg, srv and launch files,
# docs) is the program's list, `simulate --list-friction-sets` (the laws table).
add_test(NAME friction_sets_listed_test
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/docs/friction_sets_listed_test.py
          --simulate $<TARGET_FILE:simulate>)
