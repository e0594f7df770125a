# Drum pictures from a run on two ranks (rank 0 draws the gathered grains) against the one-rank
# program's: the same files at the same angles, and byte-identical while the two runs' states still
# agree to the pixel. Without settling the runs start from the same fill; their states drift apart
# in the last bits (the force sums' order differs) and reach pixel scale near 0.08 rad, so the
# pictures up to 0.03 rad (700 steps) must be identical. The summary's final measures (the drum's
# pattern, segregation and mixing indices) are the same set on both.
#   -D MPIEXEC=... -D NP_FLAG=... -D PROGRAM=grainflow_mpi -D ONE=grainflow -D SCENE=drum_quick.toml -D WORK=folder
file(REMOVE_RECURSE ${WORK})
set(common --steps 700 --threads 1 --set settle.time=0 --set output.picture_interval=0.01)
execute_process(COMMAND ${ONE} run ${SCENE} --out ${WORK}/one --quiet ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 100)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grainflow: exit status ${rc}:\n${out}")
endif()
execute_process(COMMAND ${MPIEXEC} --allow-run-as-root --oversubscribe ${NP_FLAG} 2 ${PROGRAM} run ${SCENE}
                        --out ${WORK}/two ${common}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 100)
if(NOT rc EQUAL 0 OR NOT out MATCHES "picture of the drum: [^\n]*angle_00.03.png")
  message(FATAL_ERROR "grainflow_mpi on 2 ranks: exit status ${rc}:\n${out}")
endif()
file(GLOB one RELATIVE ${WORK}/one/pictures ${WORK}/one/pictures/*.png)
file(GLOB two RELATIVE ${WORK}/two/pictures ${WORK}/two/pictures/*.png)
if(NOT one STREQUAL two OR NOT one)
  message(FATAL_ERROR "pictures on one rank: ${one}; on two: ${two}")
endif()
foreach(png ${one})
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/one/pictures/${png} ${WORK}/two/pictures/${png}
                  RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${png} drawn on two ranks differs from the one-rank picture")
  endif()
endforeach()
message(STATUS "pictures identical: ${one}")
file(READ ${WORK}/one/summary.json one_summary)
file(READ ${WORK}/two/summary.json two_summary)
string(JSON n LENGTH "${one_summary}" final)
math(EXPR last "${n} - 1")
foreach(k RANGE ${last})
  string(JSON key MEMBER "${one_summary}" final ${k})
  string(JSON value ERROR_VARIABLE missing GET "${two_summary}" final ${key})
  if(missing)
    message(FATAL_ERROR "summary.json of two ranks has no final.${key}, which the one-rank summary has")
  endif()
endforeach()
message(STATUS "summary final measures on both: ${n}")
