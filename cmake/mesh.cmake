# Meshes as convex hulls (include/nonsmooth_sim/mesh, src/mesh): a mesh file's vertices by assimp
# and their convex hull by qhull (reentrant libqhull_r), as the core's ConvexHull. A library of its
# own so that the core stays Eigen-only; the scene loader reads <mesh> through it. Debian packages:
# libassimp-dev libqhull-dev (scripts/install-deps). Its tests are test/scene_io/mesh_*_test.cpp.
find_package(assimp REQUIRED)  # assimp::assimp
find_package(Qhull REQUIRED)   # Qhull::qhull_r

file(GLOB NONSMOOTH_SIM_MESH_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/mesh/*.cpp)
add_library(nonsmooth_sim_mesh STATIC ${NONSMOOTH_SIM_MESH_SOURCES})
target_include_directories(nonsmooth_sim_mesh PUBLIC ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(nonsmooth_sim_mesh PUBLIC nonsmooth_sim_core
                      PRIVATE assimp::assimp Qhull::qhull_r)
set_target_properties(nonsmooth_sim_mesh PROPERTIES POSITION_INDEPENDENT_CODE ON)
