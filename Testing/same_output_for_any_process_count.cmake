# Runs a program under mpiexec with 1 and with 3 processes (or the counts in
# PROCESSES); each run writes PREFIX-<n>SUFFIX (ARGS holds @OUTPUT@ where that
# path goes), and the files must be equal byte for byte. WRAPPER, if set,
# runs mpiexec (a display for pvbatch's renders); with RUN_TIMEOUT (seconds)
# a run that takes longer is tried once more.
#   cmake -DMPIEXEC=... -DPREFIX=... -DSUFFIX=.npy "-DARGS=prog;arg;..." -P this
# Open MPI's hwloc would probe every X display for GPUs (and die with a
# render test's Xvfb that goes away meanwhile).
set(ENV{HWLOC_COMPONENTS} "-gl")
if (NOT PROCESSES)
  set(PROCESSES 1 3)
endif ()
list(GET PROCESSES 0 first)
foreach (processes IN LISTS PROCESSES)
  string(REPLACE "@OUTPUT@" "${PREFIX}-${processes}" arguments "${ARGS}")
  # A second try, with a warning, after RUN_TIMEOUT seconds: on a loaded
  # machine pvbatch under mpiexec now and then deadlocks in its first
  # parallel render (the first process enters IceT before the others are
  # told to render; a plain sphere does it too). Any other failure fails at
  # once, a lost X connection too (that was Xvfb resetting when its last
  # client left, which with-display's -noreset prevents).
  foreach (attempt 1 2)
    file(REMOVE "${PREFIX}-${processes}${SUFFIX}")
    set(timeout_arguments)
    if (RUN_TIMEOUT)
      set(timeout_arguments TIMEOUT ${RUN_TIMEOUT})
    endif ()
    execute_process(
      COMMAND ${WRAPPER} "${MPIEXEC}" --allow-run-as-root --oversubscribe -np ${processes} ${arguments}
      RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE errors ${timeout_arguments})
    message("${processes} processes (try ${attempt}): ${output}${errors}")
    if (NOT status MATCHES "timeout")
      break ()
    endif ()
    message(WARNING "the run on ${processes} processes timed out after ${RUN_TIMEOUT} s; trying again")
  endforeach ()
  if (NOT status EQUAL 0)
    message(FATAL_ERROR "the run on ${processes} processes failed (${status})")
  endif ()
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files
    "${PREFIX}-${first}${SUFFIX}" "${PREFIX}-${processes}${SUFFIX}" RESULT_VARIABLE differ)
  if (differ)
    message(FATAL_ERROR "the outputs of ${first} and ${processes} processes differ")
  endif ()
endforeach ()
string(REPLACE ";" ", " counts "${PROCESSES}")
message("the outputs of ${counts} processes are identical")
