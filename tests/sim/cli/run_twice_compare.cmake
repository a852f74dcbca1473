# Determinism of the whole tool: two runs with the same world, config and seed write
# byte-identical metrics.json, trajectory_truth.tum, render.png and CARMEN log; another seed
# gives a different log.
set(common --world cluttered-lab --duration 4 --seed 5 --mission manual --record)
foreach(run a b)
  file(REMOVE_RECURSE ${OUT}/${run})
  execute_process(COMMAND ${SIM} ${common} --out ${OUT}/${run} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run ${run} failed (${rc}): ${err}")
  endif()
endforeach()
foreach(f metrics.json trajectory_truth.tum render.png sim.log)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/a/${f} ${OUT}/b/${f} RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "${f} differs between two identical runs")
  endif()
endforeach()
execute_process(COMMAND ${SIM} --world cluttered-lab --duration 4 --seed 6 --mission manual --record --out ${OUT}/c
                RESULT_VARIABLE rc)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/a/sim.log ${OUT}/c/sim.log RESULT_VARIABLE diff)
if(diff EQUAL 0)
  message(FATAL_ERROR "another seed gave the same log")
endif()
