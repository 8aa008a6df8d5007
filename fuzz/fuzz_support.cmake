# The fuzz targets' checks (eqmesh_fuzz_checks) and the seed-corpus generator
# (eqmesh_fuzz_seeds, encoder side; not a fuzz target), defined once for both
# builds that need them: the fuzz build (fuzz/CMakeLists.txt) and every test
# build (tests/fuzz_regressions, whose generator CI's fuzz stage uses so that the
# fuzz build need not compile the encoder: scripts/fuzz.sh, FUZZ_SEEDS).
add_library(eqmesh_fuzz_checks STATIC "${CMAKE_CURRENT_LIST_DIR}/fuzz_checks.cpp")
target_include_directories(eqmesh_fuzz_checks PUBLIC "${PROJECT_SOURCE_DIR}" "${PROJECT_SOURCE_DIR}/lib")
target_link_libraries(eqmesh_fuzz_checks PUBLIC eqmesh_loader eqmesh_decoder eqmesh_mesh_io)

# By option, not by target: the fuzz build adds fuzz/ before lib/ defines them.
if(EQMESH_BUILD_ENCODER)
  add_executable(eqmesh_fuzz_seeds "${CMAKE_CURRENT_LIST_DIR}/make_seeds.cpp")
  target_link_libraries(eqmesh_fuzz_seeds PRIVATE eqmesh_fuzz_checks eqmesh_gltf eqmesh_encoder)
endif()
