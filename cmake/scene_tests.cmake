# Physics tests of the shipped scenes (urdf/*.urdf + config/*.yaml through the scene loader, stepped
# by the core Simulator): every test/scenes/*_test.cpp is one GoogleTest executable
# scenes_<name>, one ctest entry per TEST ("scenes.<Suite>.<Test>"), built by the `tests` target,
# the pattern of the core tests. Included from CMakeLists.txt after the core and the scene loader
# (cmake/scene_io.cmake: nonsmooth_sim_scene_io, which links nonsmooth_sim_core). The derivations
# and the numbers they check are in docs/scenes.md; each run is a few seconds in Release at most.
nonsmooth_sim_add_gtests(DIR test/scenes PREFIX scenes
                         LIBRARIES nonsmooth_sim_scene_io nonsmooth_sim_core)
