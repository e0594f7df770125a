# grainflow_mpi's checkpoints as a user meets them (cmake -P, from ctest): a run of 200 steps, and the
# same scene stopped at step 137 (checkpoints every 50 steps and at the end) then resumed with
# --resume, end with the same final_state.csv, series.csv and frames.pvd, byte for byte; the
# checkpoint resumed on three ranks is refused (exit status 2) with the index named and the fix.
#   -D MPIEXEC=... -D NP_FLAG=... -D PROGRAM=grainflow_mpi -D SCENE=checkpoint_box.toml -D WORK=folder

function(run_ranks ranks expect_rc out_var)
  execute_process(COMMAND ${MPIEXEC} --allow-run-as-root --oversubscribe ${NP_FLAG} ${ranks} ${PROGRAM} run ${SCENE}
                          --threads 1 ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 50)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "grainflow_mpi on ${ranks} ranks ${ARGN}: exit status ${rc}, expected ${expect_rc}:\n${out}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
set(every_50 --set output.checkpoint_interval=0.0005)
run_ranks(2 0 out --out ${WORK}/whole --steps 200)
run_ranks(2 0 out --out ${WORK}/split --steps 137 ${every_50})
set(index ${WORK}/split/checkpoints/checkpoint_ranks.gfc)
run_ranks(2 0 out --out ${WORK}/split --steps 200 ${every_50} --resume ${index})
if(NOT out MATCHES "resuming from [^\n]*checkpoint_ranks.gfc at step 137")
  message(FATAL_ERROR "the resumed run does not say where it resumed:\n${out}")
endif()
foreach(file final_state.csv series.csv frames.pvd)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/whole/${file} ${WORK}/split/${file}
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${file} of the resumed run differs from the uninterrupted run's")
  endif()
endforeach()

run_ranks(3 2 out --out ${WORK}/three --resume ${index})
foreach(expect "checkpoint_ranks.gfc: it was written by a run on 2 ranks, this run has 3" "mpiexec -n 2")
  string(FIND "${out}" "${expect}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the refusal on 3 ranks does not say '${expect}':\n${out}")
  endif()
endforeach()
message(STATUS "resumed run identical; 3 ranks refused:\n${out}")
