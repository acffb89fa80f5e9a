# Coverage-guided fuzzing with libFuzzer (test/fuzz, scripts/dev/fuzz; docs/testing.md, "Fuzzing").
# Off by default: with NONSMOOTH_SIM_FUZZ OFF this file defines nothing. With it ON (clang only)
# it adds the fuzz executables, each built only on request (`cmake --build <dir> --target fuzz`):
#
#   urdf_loader_fuzz        bytes = URDF text -> SceneFromUrdf -> Simulator, a few steps
#   scene_yaml_fuzz         bytes = initial-state YAML applied to shipped scenes, a few steps
#   service_sequence_fuzz   bytes -> a sequence of the node's service requests against a Simulator
#
# The fuzzed code (core, mesh hulls, scene loader, FCL pairs and the ROS-free world of world/) is
# compiled once more here into an instrumented library of its own (coverage for libFuzzer,
# AddressSanitizer, LeakSanitizer, UBSan; assertions on), so the regular libraries and every other
# target stay exactly as without the option. Included last from CMakeLists.txt (the source lists
# of the libraries are set by then).
option(NONSMOOTH_SIM_FUZZ "Build the libFuzzer targets of test/fuzz (clang only; scripts/dev/fuzz)" OFF)

if(NONSMOOTH_SIM_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "NONSMOOTH_SIM_FUZZ needs clang (libFuzzer), got ${CMAKE_CXX_COMPILER_ID}: "
                        "configure with -DCMAKE_CXX_COMPILER=clang++ (scripts/dev/fuzz does)")
  endif()
  # every sanitizer finding aborts (libFuzzer then writes the input as crash-<sha1>); -UNDEBUG
  # keeps Eigen's index and size assertions
  set(NONSMOOTH_SIM_FUZZ_SANITIZERS
      -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  set(NONSMOOTH_SIM_FUZZ_COMPILE ${NONSMOOTH_SIM_FUZZ_SANITIZERS} -gline-tables-only -UNDEBUG)

  add_library(nonsmooth_sim_fuzz_instrumented STATIC EXCLUDE_FROM_ALL
    ${NONSMOOTH_SIM_CORE_SOURCES}
    ${NONSMOOTH_SIM_MESH_SOURCES}
    ${NONSMOOTH_SIM_SCENE_IO_SOURCES}
    ${NONSMOOTH_SIM_COLLISION_FCL_SOURCES}
    ${NONSMOOTH_SIM_WORLD_SOURCES})  # ROS-free: the world the node serves
  target_include_directories(nonsmooth_sim_fuzz_instrumented PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_compile_options(nonsmooth_sim_fuzz_instrumented PRIVATE
    -fsanitize=fuzzer-no-link ${NONSMOOTH_SIM_FUZZ_COMPILE})
  target_link_libraries(nonsmooth_sim_fuzz_instrumented
    PUBLIC Eigen3::Eigen fcl
    PRIVATE urdfdom::urdfdom_model tinyxml2::tinyxml2 yaml-cpp assimp::assimp Qhull::qhull_r)

  add_custom_target(fuzz)
  foreach(name urdf_loader_fuzz scene_yaml_fuzz service_sequence_fuzz)
    add_executable(${name} EXCLUDE_FROM_ALL ${PROJECT_SOURCE_DIR}/test/fuzz/${name}.cpp)
    target_compile_options(${name} PRIVATE -fsanitize=fuzzer ${NONSMOOTH_SIM_FUZZ_COMPILE})
    target_link_options(${name} PRIVATE -fsanitize=fuzzer ${NONSMOOTH_SIM_FUZZ_SANITIZERS})
    target_link_libraries(${name} PRIVATE nonsmooth_sim_fuzz_instrumented)
    target_compile_definitions(${name} PRIVATE NONSMOOTH_SIM_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
    set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz_bin)
    add_dependencies(fuzz ${name})
  endforeach()
endif()
