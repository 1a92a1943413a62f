# Installs this build into a fresh prefix and checks what a user finds there:
# both programs (their --version the project's), their manual pages and
# bash/zsh completions, and a pkg-config file through which a one-line
# program compiles against the engine and runs.
#   cmake -DBUILD_DIR=... -DWORK_DIR=... -DVERSION=... -DCXX=... -DMANUALS=ON|OFF -P installed_tree.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
include(${CMAKE_CURRENT_LIST_DIR}/run.cmake)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
file(GLOB pc ${prefix}/lib*/pkgconfig/particles.pc)
set(expected bin/particle-lab share/bash-completion/completions/particle-lab share/zsh/vendor-completions/_particle-lab)
if(MANUALS)
  list(APPEND expected share/man/man1/particle-lab.1)
endif()
foreach(file IN LISTS expected)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the installed tree has no ${file}")
  endif()
endforeach()
if(NOT pc)
  message(FATAL_ERROR "the installed tree has no lib*/pkgconfig/particles.pc")
endif()
run(${prefix}/bin/particle-lab --version)
if(NOT out STREQUAL "particle-lab ${VERSION}\n")
  message(FATAL_ERROR "installed particle-lab --version printed '${out}', expected 'particle-lab ${VERSION}'")
endif()
file(WRITE ${WORK_DIR}/app.cpp [=[
#include <cstdio>
#include <memory>
#include <particles/particles.h>
int main() {
  particles::ParticleSystem system;
  system.addParticle({0.0, 0.0}, 1.0);
  system.addForce(std::make_unique<particles::GravityForce>(Eigen::Vector2d(0.0, -2.0)));
  auto integrator = particles::makeIntegrator("rk4");
  system.step(*integrator, 0.5);  // exact for constant acceleration: y = -t^2
  std::printf("y = %g\n", system.position(0).y());
  return system.position(0).y() == -0.25 ? 0 : 1;
}
]=])
get_filename_component(pcdir ${pc} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
run(pkg-config --cflags --libs particles)
separate_arguments(flags UNIX_COMMAND "${out}")
run(${CXX} -std=c++17 ${WORK_DIR}/app.cpp -o ${WORK_DIR}/app ${flags})
run(${WORK_DIR}/app)
message(STATUS "${out}installed tree: ${expected}; pkg-config build ran")
