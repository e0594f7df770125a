# Feeds and outlets on ranks (cmake -P, from ctest), on flow_box.toml: grains fed over the whole width
# of a box land on both ranks' sides, cross the cut and leave through an outlet in its floor.
#  - grainflow_mpi on one rank against grainflow: final_state.csv and residence.csv byte for byte
#    (the same grains fed, moved and counted out); series.csv and layers.csv within 1e-12, their
#    measures of all the grains (segregation, Lacey, Vc) being summed in id order on rank 0 rather
#    than in row order (measured: the last two digits);
#  - on two ranks: as many grains fed as on one (every rank draws the same grains), and every grain
#    either held or counted out, once (rank_flow_check.py conserved);
#  - stopped at step 1350 (right after an outlet check, so the checkpoint holds grains queued to leave) and resumed on two ranks: the four files byte for byte as the run that was
#    not stopped; resumed on one rank from the same checkpoint: every grain still accounted for.
#   -D MPIEXEC=... -D NP_FLAG=... -D PROGRAM=grainflow_mpi -D ONE=grainflow -D SCENE=flow_box.toml
#   -D WORK=folder -D PYTHON=python3
set(fill 240)  # grains of the scene's fill
set(check ${CMAKE_CURRENT_LIST_DIR}/rank_flow_check.py)

function(run_ranks ranks)
  execute_process(COMMAND ${MPIEXEC} --allow-run-as-root --oversubscribe ${NP_FLAG} ${ranks} ${PROGRAM} run ${SCENE}
                          --threads 1 ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 100)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "grainflow_mpi on ${ranks} ranks ${ARGN}: exit status ${rc}:\n${out}")
  endif()
endfunction()

function(python_check)
  execute_process(COMMAND ${PYTHON} ${check} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE said)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${said}")
  endif()
  message(STATUS "${said}")
endfunction()

include(${CMAKE_CURRENT_LIST_DIR}/same_files.cmake)

function(fed_grains run var)
  file(READ ${run}/summary.json summary)
  string(JSON n GET "${summary}" flow fed_grains)
  set(${var} ${n} PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${ONE} run ${SCENE} --out ${WORK}/one --threads 1 --quiet
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out TIMEOUT 100)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "grainflow: exit status ${rc}:\n${out}")
endif()
python_check(conserved ${WORK}/one ${fill})

run_ranks(1 --out ${WORK}/rank1)
same_files(${WORK}/one ${WORK}/rank1 final_state.csv residence.csv)
python_check(same ${WORK}/one/series.csv ${WORK}/rank1/series.csv 1e-12)
python_check(same ${WORK}/one/layers.csv ${WORK}/rank1/layers.csv 1e-12)

run_ranks(2 --out ${WORK}/two)
python_check(conserved ${WORK}/two ${fill})
fed_grains(${WORK}/one one_fed)
fed_grains(${WORK}/two two_fed)
if(NOT one_fed EQUAL two_fed OR one_fed LESS 100)
  message(FATAL_ERROR "grains fed: ${two_fed} on two ranks, ${one_fed} on one (at least 100 expected)")
endif()

set(every --set output.checkpoint_interval=0.005)
run_ranks(2 --out ${WORK}/split --steps 1350 ${every})
file(COPY ${WORK}/split/ DESTINATION ${WORK}/on1)
run_ranks(2 --out ${WORK}/split --steps 3000 ${every} --resume ${WORK}/split/checkpoints/checkpoint_ranks.gfc)
same_files(${WORK}/two ${WORK}/split final_state.csv series.csv residence.csv layers.csv)
run_ranks(1 --out ${WORK}/on1 --steps 3000 ${every} --resume ${WORK}/on1/checkpoints/checkpoint_ranks.gfc)
python_check(conserved ${WORK}/on1 ${fill})

# A feed far from every starting grain (one grain on the floor, the feed 2.9 m above it): the domain
# the ranks' boxes tile is cut around the feed's region too, so its grains do not stop the run as
# grains that left the domain (the domain is widened a thousandfold around the starting grains alone
# otherwise, here 1 m).
run_ranks(2 --out ${WORK}/far --set "fill.0.region.hi=[0.001,0.001,0.001]" --set fill.0.count.small=1
          --set "wall.0.hi=[0.06,3.0,0.01]" --set "feed.0.region.lo=[0.002,2.9,0.0]"
          --set "feed.0.region.hi=[0.058,2.906,0.01]" --set run.duration=0.005)
python_check(conserved ${WORK}/far 1)
message(STATUS "feeds and outlets: one rank as grainflow, two ranks accounted for, resumed byte for byte")
