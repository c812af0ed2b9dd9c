# Runs a program under mpiexec with 1 and with 3 processes; each run writes
# PREFIX-<n>SUFFIX (ARGS holds @OUTPUT@ where that path goes), and the two
# files must be equal byte for byte.
#   cmake -DMPIEXEC=... -DPREFIX=... -DSUFFIX=.npy "-DARGS=prog;arg;..." -P this
# Open MPI's hwloc would probe every X display for GPUs (and die with a
# render test's Xvfb that goes away meanwhile).
set(ENV{HWLOC_COMPONENTS} "-gl")
foreach (processes 1 3)
  string(REPLACE "@OUTPUT@" "${PREFIX}-${processes}" arguments "${ARGS}")
  file(REMOVE "${PREFIX}-${processes}${SUFFIX}")
  execute_process(
    COMMAND "${MPIEXEC}" --allow-run-as-root --oversubscribe -np ${processes} ${arguments}
    RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE errors)
  message("${processes} processes: ${output}${errors}")
  if (NOT status EQUAL 0)
    message(FATAL_ERROR "the run on ${processes} processes failed (${status})")
  endif ()
endforeach ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
  "${PREFIX}-1${SUFFIX}" "${PREFIX}-3${SUFFIX}" RESULT_VARIABLE differ)
if (differ)
  message(FATAL_ERROR "the outputs of 1 and 3 processes differ")
endif ()
message("the outputs of 1 and 3 processes are identical")
