# particles_target_options(<target>): the language level, warnings and (with
# PARTICLES_SANITIZE) sanitizers of every target this project builds, scoped to
# the target so a project that adds this tree keeps its own flags.
function(particles_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(PARTICLES_SANITIZE)
    # float-cast-overflow (a double too large for an int) is not part of "undefined" in GCC.
    set(flags -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=all)
    target_compile_options(${target} PRIVATE ${flags})
    target_link_options(${target} PRIVATE -fsanitize=address,undefined,float-cast-overflow)
  endif()
endfunction()
