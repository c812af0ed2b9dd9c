# Installs the build tree into a scratch prefix, then configures, builds and
# runs a separate project that finds the package with find_package().
# Arguments: BUILD_DIR, SOURCE_DIR, WORK_DIR; with PYTHON and
# PYTHON_DESTINATION, also imports the installed Python package.
file(REMOVE_RECURSE "${WORK_DIR}")
set(prefix "${WORK_DIR}/prefix")
function (run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif ()
  message("${out}")
endfunction ()
run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
foreach (file IN ITEMS
    "lib/cmake/MonteCarloXRay/MonteCarloXRayConfig.cmake"
    "include/MonteCarloXRay/vtkMCXProjector.h"
    "bin/mcxray"
    "share/MonteCarloXRay/ct_head_headsq.vti")
  if (NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${file}")
  endif ()
endforeach ()
run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/Testing/Install/consumer" -B "${WORK_DIR}/consumer"
  "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_BUILD_TYPE=Release)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer")
run("${WORK_DIR}/consumer/consumer")
# The Filters component brings no OpenGL: neither the consumer nor the
# installed Filters library loads VTK's OpenGL rendering or GLEW.
foreach (binary IN ITEMS "${WORK_DIR}/consumer/consumer" "${prefix}/lib/libMonteCarloXRayFilters.so")
  execute_process(COMMAND ldd "${binary}" OUTPUT_VARIABLE libraries RESULT_VARIABLE result)
  if (NOT result EQUAL 0 OR NOT libraries MATCHES "libvtkCommonCore")
    message(FATAL_ERROR "ldd failed on ${binary}")
  endif ()
  if (libraries MATCHES "RenderingOpenGL2|glew|libGL")
    message(FATAL_ERROR "${binary} loads OpenGL:\n${libraries}")
  endif ()
endforeach ()
# The package still gives the three components, and the whole.
file(WRITE "${WORK_DIR}/components/CMakeLists.txt" "cmake_minimum_required(VERSION 3.16)
project(Components LANGUAGES C CXX)
find_package(MonteCarloXRay REQUIRED COMPONENTS Filters Rendering IO)
foreach (target IN ITEMS MonteCarloXRay::Filters MonteCarloXRay::Rendering MonteCarloXRay::IO
    MonteCarloXRay::MonteCarloXRay)
  if (NOT TARGET \${target})
    message(FATAL_ERROR \"missing \${target}\")
  endif ()
endforeach ()
find_package(MonteCarloXRay COMPONENTS NoSuchPart)
if (MonteCarloXRay_FOUND)
  message(FATAL_ERROR \"an unknown component was found\")
endif ()
")
run("${CMAKE_COMMAND}" -S "${WORK_DIR}/components" -B "${WORK_DIR}/components/build" "-DCMAKE_PREFIX_PATH=${prefix}")
run("${prefix}/bin/mcxray" --help)
if (PYTHON)
  set(ENV{PYTHONPATH} "${prefix}/${PYTHON_DESTINATION}")
  run("${PYTHON}" "${SOURCE_DIR}/Testing/Install/check_python_package.py")
endif ()
