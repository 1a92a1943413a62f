# The WebAssembly build's dependencies (Emscripten; scripts/build-web.sh).
# Eigen, CLI11, nlohmann-json, {fmt} and Boost are header-only here, taken
# from the host's Debian packages: their folders are linked into one staging
# folder (the host's /usr/include itself must not reach em++, whose C library
# is another), and each package's find_package() finds a config file written
# below, which names the imported target this tree links to.
set(PARTICLES_HOST_INCLUDE /usr/include CACHE PATH "where the host's header-only libraries are")
set(staged ${CMAKE_BINARY_DIR}/host-headers)
file(MAKE_DIRECTORY ${staged})
foreach(entry eigen3/Eigen eigen3/unsupported CLI nlohmann fmt boost)
  get_filename_component(name ${entry} NAME)
  if(NOT EXISTS ${PARTICLES_HOST_INCLUDE}/${entry})
    message(FATAL_ERROR "${PARTICLES_HOST_INCLUDE}/${entry} not found (scripts/install-deps.sh installs it)")
  endif()
  if(NOT EXISTS ${staged}/${name})
    file(CREATE_LINK ${PARTICLES_HOST_INCLUDE}/${entry} ${staged}/${name} SYMBOLIC)
  endif()
endforeach()

# package name, its target, the version it reports, and its compile definitions
set(web_packages
  "Eigen3|Eigen3::Eigen|3.4.0|"
  "CLI11|CLI11::CLI11|2.1.2|"
  "nlohmann_json|nlohmann_json::nlohmann_json|3.11.2|"
  "fmt|fmt::fmt|9.1.0|FMT_HEADER_ONLY"
  "Boost|Boost::boost|1.74.0|")
set(configs ${CMAKE_BINARY_DIR}/web-packages)
foreach(package IN LISTS web_packages)
  string(REPLACE "|" ";" fields "${package}")
  list(GET fields 0 name)
  list(GET fields 1 target)
  list(GET fields 2 version)
  list(LENGTH fields count)
  set(definitions "")
  if(count GREATER 3)
    list(GET fields 3 definitions)
  endif()
  file(WRITE ${configs}/${name}/${name}Config.cmake
    "if(NOT TARGET ${target})\n"
    "  add_library(${target} INTERFACE IMPORTED)\n"
    "  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES \"${staged}\"\n"
    "    INTERFACE_COMPILE_DEFINITIONS \"${definitions}\")\n"
    "endif()\n")
  file(WRITE ${configs}/${name}/${name}ConfigVersion.cmake
    "set(PACKAGE_VERSION ${version})\n"
    "set(PACKAGE_VERSION_COMPATIBLE TRUE)\n"
    "if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)\n"
    "  set(PACKAGE_VERSION_COMPATIBLE FALSE)\n"
    "endif()\n")
  set(${name}_DIR ${configs}/${name} CACHE PATH "" FORCE)
endforeach()
# FindBoost takes Boost_DIR's config file rather than searching.
set(Boost_NO_SYSTEM_PATHS ON)
