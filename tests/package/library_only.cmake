# Configures the engine alone (no demos, no tests: neither GLUT, CLI11 nor
# GoogleTest is looked for) as a shared library, builds and installs it, then
# builds and runs the consumer project against the installed package. The
# engine is built unoptimised and without debug information (Debug, -O0): what
# is checked is what gets installed and that it links and runs, and -O0
# compiles in a fraction of the time.
#   cmake -DSOURCE_TREE=... -DCONSUMER=... -DWORK_DIR=... -DGENERATOR=... -P library_only.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
run(${CMAKE_COMMAND} -S ${SOURCE_TREE} -B ${WORK_DIR}/engine -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0
    -DBUILD_SHARED_LIBS=ON -DPARTICLES_BUILD_DEMOS=OFF -DPARTICLES_BUILD_TESTS=OFF -DPARTICLES_INSTALL=ON)
if(out MATCHES "GTest|GLUT|CLI11")
  message(FATAL_ERROR "the library-only configure looked for a tool's dependency:\n${out}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/engine -j 2)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/engine --prefix ${prefix})
file(GLOB_RECURSE shared ${prefix}/libparticles.so*)
if(NOT shared)
  message(FATAL_ERROR "no libparticles.so under ${prefix}")
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER} -B ${WORK_DIR}/consumer -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
set(ENV{LD_LIBRARY_PATH} "")
run(${WORK_DIR}/consumer/consumer)
message(STATUS "${out}")
