# Install rules and the exported CMake package: find_package(Tumble) -> Tumble::tumble.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(tumble PROPERTIES EXPORT_NAME tumble)
install(TARGETS tumble_core tumble_collision tumble_solver tumble_engine tumble
        EXPORT TumbleTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir core collision solver engine)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()

set(TUMBLE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tumble)
install(EXPORT TumbleTargets NAMESPACE Tumble:: DESTINATION ${TUMBLE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TumbleConfig.cmake.in
  ${PROJECT_BINARY_DIR}/TumbleConfig.cmake INSTALL_DESTINATION ${TUMBLE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TumbleConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/TumbleConfig.cmake ${PROJECT_BINARY_DIR}/TumbleConfigVersion.cmake
        DESTINATION ${TUMBLE_CMAKE_DIR})
