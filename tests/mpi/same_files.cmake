# same_files(A B FILE...): every FILE (a path under both folders) byte-identical in B as in A, or the
# test stops naming the first that differs. Included by the scripts that compare runs.
function(same_files a b)
  foreach(file ${ARGN})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${a}/${file} ${b}/${file} RESULT_VARIABLE differ)
    if(differ)
      message(FATAL_ERROR "${b}/${file} differs from ${a}/${file}")
    endif()
  endforeach()
endfunction()
