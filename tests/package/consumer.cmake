# Installs this build of particles into a fresh prefix, then configures, builds
# and runs the consumer project against it with find_package(particles).
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -P consumer.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
if(NOT EXISTS ${prefix}/lib/cmake/particles/particlesConfig.cmake AND
   NOT EXISTS ${prefix}/lib64/cmake/particles/particlesConfig.cmake)
  file(GLOB_RECURSE found ${prefix}/*particlesConfig.cmake)
  if(NOT found)
    message(FATAL_ERROR "no particlesConfig.cmake under ${prefix}")
  endif()
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
message(STATUS "${out}")
