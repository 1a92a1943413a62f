# particle-lab export --scene SCENE, then the exported file and the built-in
# scene each run STEPS steps with a trajectory of every step: the two
# trajectories must be identical byte for byte.
set(file "${DIR}/${SCENE}.json")
execute_process(COMMAND ${PROGRAM} export --scene ${SCENE} --output ${file} RESULT_VARIABLE code)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "export --scene ${SCENE} failed: ${code}")
endif()
foreach(source "--scene;${SCENE}" "--scene-file;${file}")
  list(GET source 0 option)
  execute_process(COMMAND ${PROGRAM} run ${source} --steps ${STEPS} --trajectory ${DIR}/${SCENE}${option}.csv
                  RESULT_VARIABLE code OUTPUT_QUIET)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "run ${source} failed: ${code}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${DIR}/${SCENE}--scene.csv ${DIR}/${SCENE}--scene-file.csv
                RESULT_VARIABLE different)
if(different)
  message(FATAL_ERROR "the exported ${SCENE} steps differently from the built-in one")
endif()
