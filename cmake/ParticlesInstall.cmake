# Installs particles::particles as a CMake package:
#   find_package(particles 0.2 REQUIRED)
#   target_link_libraries(app PRIVATE particles::particles)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PARTICLES_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/particles)
install(TARGETS particles EXPORT particlesTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/particles DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT particlesTargets NAMESPACE particles:: DESTINATION ${PARTICLES_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/particlesConfig.cmake.in
  ${PROJECT_BINARY_DIR}/particlesConfig.cmake INSTALL_DESTINATION ${PARTICLES_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/particlesConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/particlesConfig.cmake ${PROJECT_BINARY_DIR}/particlesConfigVersion.cmake
        DESTINATION ${PARTICLES_CMAKE_DIR})
