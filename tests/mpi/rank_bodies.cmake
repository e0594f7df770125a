# Composite bodies on two ranks (and three) against grainflow on one process: every file the run
# writes (series.csv, frames, pictures, packing.csv, the checkpoint) byte for byte, and a run stopped at a
# checkpoint and resumed on two ranks, on one (grainflow_mpi) and by grainflow ends with the same
# files as the run that was not stopped. The split of the contacts keeps one process's order of
# every sum (body_contact_split.hpp), so nothing is compared with a tolerance.
#   -D MPIEXEC=... -D NP_FLAG=... -D PROGRAM=grainflow_mpi -D ONE=grainflow -D SCENE=hopper_mixed_prisms_spheres.toml -D WORK=folder
file(REMOVE_RECURSE ${WORK})
set(common --threads 1 --quiet --set bodies.2.count=60 --set fill.0.count.glass=30 --set settle.time=0.3
    --set run.duration=0.2 --set output.series_interval=0.01 --set output.frame_interval=0.05
    --set output.picture_interval=0.05 --set output.checkpoint_interval=0.1)
set(mpi ${MPIEXEC} --allow-run-as-root --oversubscribe)

function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 250)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what}: exit status ${rc}:\n${out}")
  endif()
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/same_files.cmake)

# Every file of `ref` but summary.json is in `dir` with the same bytes.
function(same_outputs ref dir what)
  file(GLOB_RECURSE files RELATIVE ${ref} ${ref}/*)
  list(REMOVE_ITEM files summary.json)
  list(LENGTH files n)
  if(n LESS 10)
    message(FATAL_ERROR "${ref} holds ${n} files: ${files}")
  endif()
  same_files(${ref} ${dir} ${files})
  message(STATUS "${what}: ${n} files byte-identical")
endfunction()

run_checked("grainflow" ${ONE} run ${SCENE} --out ${WORK}/one ${common})
run_checked("grainflow_mpi on 2 ranks" ${mpi} ${NP_FLAG} 2 ${PROGRAM} run ${SCENE} --out ${WORK}/two ${common})
same_outputs(${WORK}/one ${WORK}/two "2 ranks")
run_checked("grainflow_mpi on 3 ranks" ${mpi} ${NP_FLAG} 3 ${PROGRAM} run ${SCENE} --out ${WORK}/three ${common})
same_outputs(${WORK}/one ${WORK}/three "3 ranks")
file(READ ${WORK}/two/summary.json summary)
string(JSON ranks GET "${summary}" ranks)
string(JSON status GET "${summary}" status)
if(NOT ranks EQUAL 2 OR NOT status STREQUAL "completed")
  message(FATAL_ERROR "summary.json of 2 ranks: ranks ${ranks}, status ${status}")
endif()

# Stopped at 0.1 s (its checkpoint written at the end), then resumed three ways from copies.
run_checked("the first half on 2 ranks" ${mpi} ${NP_FLAG} 2 ${PROGRAM} run ${SCENE} --out ${WORK}/half ${common} --steps 2500)
foreach(way two one grainflow)
  file(COPY ${WORK}/half/ DESTINATION ${WORK}/resumed_${way})
  set(resume --out ${WORK}/resumed_${way} ${common} --resume ${WORK}/resumed_${way}/checkpoints/checkpoint.gfc)
  if(way STREQUAL "two")
    run_checked("resumed on 2 ranks" ${mpi} ${NP_FLAG} 2 ${PROGRAM} run ${SCENE} ${resume})
  elseif(way STREQUAL "one")
    run_checked("resumed on 1 rank" ${mpi} ${NP_FLAG} 1 ${PROGRAM} run ${SCENE} ${resume})
  else()
    run_checked("resumed by grainflow" ${ONE} run ${SCENE} ${resume})
  endif()
  same_outputs(${WORK}/one ${WORK}/resumed_${way} "resumed (${way})")
endforeach()
