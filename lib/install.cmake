# `cmake --install` rules: the decoder's C API as eqmesh::decoder (the static
# libraries it is made of, its header include/eqmesh/eqmesh.h, the decoder-side C++
# headers under include/eqmesh/ for C++ users) and an eqmeshConfig.cmake that
# find_package(eqmesh) reads.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(EQMESH_DECODER_TARGETS eqmesh_capi eqmesh_decoder eqmesh_eq_decoder eqmesh_zerotree eqmesh_entropy
    eqmesh_quantizer_model eqmesh_wavelet eqmesh_mesh eqmesh_core)
set_target_properties(eqmesh_capi PROPERTIES EXPORT_NAME decoder)
install(TARGETS ${EQMESH_DECODER_TARGETS} EXPORT eqmeshTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(FILES "${PROJECT_SOURCE_DIR}/include/eqmesh/eqmesh.h" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/eqmesh)
foreach(dir core mesh wavelet coding)
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
