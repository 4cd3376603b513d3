# Install rules and the exported CMake package: find_package(Tumble) -> Tumble::tumble.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(tumble PROPERTIES EXPORT_NAME tumble)
install(TARGETS tumble_core tumble_collision tumble_solver tumble_engine tumble
        EXPORT TumbleTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The headers an application may include: the API and the vocabulary it shows, listed in
# docs/ARCHITECTURE.md (Public headers). Nothing else is installed -- not solver/ nor collision's
# broadphase and narrowphase -- so a public header that reached an internal one would not
# compile; tests/package compiles each installed header on its own and compares the set with
# that list.
set(TUMBLE_PUBLIC_HEADERS
  core/tumble/core/error.h
  core/tumble/core/mass.h
  core/tumble/core/math.h
  core/tumble/core/solver_types.h
  collision/tumble/collision/aabb.h
  collision/tumble/collision/manifold.h
  collision/tumble/collision/shape.h
  engine/tumble/body.h
  engine/tumble/checkpoint.h
  engine/tumble/contact.h
  engine/tumble/control.h
  engine/tumble/debug_draw.h
  engine/tumble/events.h
  engine/tumble/joint.h
  engine/tumble/lumped.h
  engine/tumble/query.h
  engine/tumble/shape.h
  engine/tumble/spring.h
  engine/tumble/tumble.h
  engine/tumble/types.h
  engine/tumble/warnings.h
  engine/tumble/world.h)
foreach(entry ${TUMBLE_PUBLIC_HEADERS})
  string(REGEX MATCH "^([a-z]+)/(.+)$" _ ${entry})  # the library's folder, the include path
  set(header ${CMAKE_MATCH_2})
  get_filename_component(subdir ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${CMAKE_MATCH_1}/include/${header}
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${subdir})
endforeach()

set(TUMBLE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tumble)
install(EXPORT TumbleTargets NAMESPACE Tumble:: DESTINATION ${TUMBLE_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TumbleConfig.cmake.in
  ${PROJECT_BINARY_DIR}/TumbleConfig.cmake INSTALL_DESTINATION ${TUMBLE_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TumbleConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/TumbleConfig.cmake ${PROJECT_BINARY_DIR}/TumbleConfigVersion.cmake
        DESTINATION ${TUMBLE_CMAKE_DIR})
