# `cmake --install` rules: the decoder's C API as eqmesh::decoder (the static
# libraries it is made of, its header include/eqmesh/eqmesh.h, the decoder-side C++
# headers under include/eqmesh/ for C++ users); where the encoder is built, also
# eqmesh::loader (glTF files through TinyGLTF, compressed primitives decoded),
# eqmesh::encoder (remesher and stream encoder) and eqmesh::gltf_converter (glTF in,
# compressed glTF out); and an eqmeshConfig.cmake that find_package(eqmesh) reads.
# Eigen is a build-time dependency only (BUILD_INTERFACE in lib/mesh): the C API
# never needs it, and the package config gives it to C++ users where it is found.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(EQMESH_INSTALL_TARGETS eqmesh_capi eqmesh_decoder eqmesh_eq_decoder eqmesh_zerotree eqmesh_entropy
    eqmesh_quantizer_model eqmesh_wavelet eqmesh_mesh eqmesh_core)
set(EQMESH_HEADER_DIRS core mesh wavelet coding)
set_target_properties(eqmesh_capi PROPERTIES EXPORT_NAME decoder)
if(EQMESH_BUILD_ENCODER)
  set_target_properties(eqmesh_loader PROPERTIES EXPORT_NAME loader)
  set_target_properties(eqmesh_encoder PROPERTIES EXPORT_NAME encoder)
  set_target_properties(eqmesh_gltf PROPERTIES EXPORT_NAME gltf_converter)
  list(APPEND EQMESH_INSTALL_TARGETS eqmesh_loader eqmesh_mesh_io eqmesh_encoder eqmesh_eq_encoder eqmesh_remesh
       eqmesh_metrics eqmesh_threads eqmesh_texture eqmesh_gltf)
  list(APPEND EQMESH_HEADER_DIRS mesh_io metrics remesh texture gltf)
endif()
install(TARGETS ${EQMESH_INSTALL_TARGETS} EXPORT eqmeshTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES "${PROJECT_SOURCE_DIR}/include/eqmesh/eqmesh.h" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/eqmesh)
foreach(dir ${EQMESH_HEADER_DIRS})
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/lib/${dir}" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/eqmesh
          FILES_MATCHING PATTERN "*.h" PATTERN "*.inc")
endforeach()
install(EXPORT eqmeshTargets NAMESPACE eqmesh:: FILE eqmeshTargets.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/eqmesh)
configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/eqmeshConfig.cmake.in"
                              "${PROJECT_BINARY_DIR}/eqmeshConfig.cmake"
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/eqmesh)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/eqmeshConfigVersion.cmake" COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/eqmeshConfig.cmake" "${PROJECT_BINARY_DIR}/eqmeshConfigVersion.cmake"
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/eqmesh)
