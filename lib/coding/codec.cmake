# Codec assembly: the .eqm container, base-mesh chunk, closed-loop encoder, decoder.
# eqmesh_decoder is decoder-side (never links encoder code or the remesher);
# eqmesh_encoder links it so both sides share one bitstream definition.
set(EQMESH_CODEC_DIR "${CMAKE_CURRENT_LIST_DIR}")

eqmesh_sources_in(${PROJECT_SOURCE_DIR}/lib EQMESH_STREAM_DECODER_SOURCES stream_decoder_sources)
if(EQMESH_WITH_DRACO)
  add_library(eqmesh_decoder STATIC ${stream_decoder_sources} ${EQMESH_CODEC_DIR}/base_mesh_decoder.cpp)
  target_link_libraries(eqmesh_decoder PRIVATE draco::draco)
else()
  add_library(eqmesh_decoder STATIC ${stream_decoder_sources} ${EQMESH_CODEC_DIR}/base_mesh_decoder_no_draco.cpp)
endif()
target_include_directories(eqmesh_decoder PUBLIC "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/lib>" "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/eqmesh>")
# draco's imported targets lack Eigen's include path, so Eigen comes first via mesh.
target_link_libraries(eqmesh_decoder PUBLIC eqmesh_eq_decoder eqmesh_zerotree eqmesh_entropy eqmesh_wavelet
                      eqmesh_mesh $<BUILD_INTERFACE:Eigen3::Eigen>)

if(NOT EQMESH_BUILD_ENCODER)
  return()
endif()

add_library(eqmesh_encoder STATIC
  ${EQMESH_CODEC_DIR}/atlas/attach_atlas.cpp
  ${EQMESH_CODEC_DIR}/compact_base/compact_base_encoder.cpp
  ${EQMESH_CODEC_DIR}/base_mesh_encoder.cpp
  ${EQMESH_CODEC_DIR}/semi_regular_reorder.cpp
  ${EQMESH_CODEC_DIR}/base_influence.cpp
  ${EQMESH_CODEC_DIR}/level_encoder.cpp
  ${EQMESH_CODEC_DIR}/closed_loop.cpp
  ${EQMESH_CODEC_DIR}/zerotree_encoder.cpp
  ${EQMESH_CODEC_DIR}/encoder.cpp
  ${EQMESH_CODEC_DIR}/level_count_search.cpp
  ${EQMESH_CODEC_DIR}/representation_choice.cpp
  ${EQMESH_CODEC_DIR}/base_size_walk.cpp
  ${EQMESH_CODEC_DIR}/stream_psnr.cpp
  ${EQMESH_CODEC_DIR}/rate_control.cpp)
target_link_libraries(eqmesh_encoder PUBLIC eqmesh_decoder eqmesh_eq_encoder eqmesh_threads PRIVATE draco::draco)
# lib/remesh is added after lib/coding, so test for its directory, not its target.
if(EXISTS "${PROJECT_SOURCE_DIR}/lib/remesh/CMakeLists.txt")
  target_link_libraries(eqmesh_encoder PUBLIC eqmesh_remesh)
endif()
if(TARGET eqmesh_metrics)
  target_link_libraries(eqmesh_encoder PUBLIC eqmesh_metrics)
  target_compile_definitions(eqmesh_encoder PRIVATE EQMESH_HAVE_METRICS=1)
endif()

