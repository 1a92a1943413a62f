# Installs particles::particles as a CMake package and a pkg-config file:
#   find_package(particles 0.2 REQUIRED)
#   target_link_libraries(app PRIVATE particles::particles)
# or  c++ -std=c++17 app.cpp $(pkg-config --cflags --libs particles)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(PARTICLES_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/particles)
install(TARGETS particles EXPORT particlesTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/particles DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT particlesTargets NAMESPACE particles:: DESTINATION ${PARTICLES_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/particlesConfig.cmake.in
  ${PROJECT_BINARY_DIR}/particlesConfig.cmake INSTALL_DESTINATION ${PARTICLES_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/particlesConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/particlesConfig.cmake ${PROJECT_BINARY_DIR}/particlesConfigVersion.cmake
        DESTINATION ${PARTICLES_CMAKE_DIR})
# The .pc file finds the prefix from its own place (pcfiledir), so the tree
# can be installed anywhere (cmake --install --prefix).
file(RELATIVE_PATH PARTICLES_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
configure_file(${PROJECT_SOURCE_DIR}/cmake/particles.pc.in ${PROJECT_BINARY_DIR}/particles.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/particles.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
