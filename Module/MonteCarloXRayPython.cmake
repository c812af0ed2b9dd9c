# The Python package `mcxray`: the classes of the three modules (Filters,
# Rendering and IO) wrapped by VTK's wrapper, plus NumPy helpers in
# __init__.py and the NumPy-first DRR API in drr.py. Importable by Debian's
# /usr/bin/python3 (with python3-vtk9) from the build tree (PYTHONPATH=<build>/${MCXRAY_PYTHON_DESTINATION})
# and after `cmake --install` to a prefix whose dist-packages Python searches.
vtk_module_python_default_destination(mcxray_python_default)
if (EXISTS "/usr/lib/python3/dist-packages" AND DEFINED Python3_VERSION_MINOR)
  # Debian's Python (the one VTK wraps for) searches
  # <prefix>/lib/python3.X/dist-packages for /usr/local and other prefixes.
  set(mcxray_python_default "lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages")
endif ()
set(MCXRAY_PYTHON_DESTINATION "${mcxray_python_default}"
  CACHE STRING "Where the mcxray Python package goes, relative to the prefix")

vtk_module_wrap_python(
  MODULES             ${mcxray_modules}
  TARGET              MonteCarloXRay::Python
  INSTALL_EXPORT      MonteCarloXRayPython
  PYTHON_PACKAGE      "mcxray"
  MODULE_DESTINATION  "${MCXRAY_PYTHON_DESTINATION}"
  CMAKE_DESTINATION   "${CMAKE_INSTALL_LIBDIR}/cmake/MonteCarloXRay"
  LIBRARY_DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  BUILD_STATIC        OFF
  INSTALL_HEADERS     OFF)

configure_file("${CMAKE_CURRENT_LIST_DIR}/Python/__init__.py.in"
  "${CMAKE_BINARY_DIR}/${MCXRAY_PYTHON_DESTINATION}/mcxray/__init__.py" @ONLY)
# The pure-Python modules, copied as they are (configure_file re-copies on change).
set(mcxray_python_modules drr.py polychromatic.py presets.py)
foreach (module IN LISTS mcxray_python_modules)
  configure_file("${CMAKE_CURRENT_LIST_DIR}/Python/${module}"
    "${CMAKE_BINARY_DIR}/${MCXRAY_PYTHON_DESTINATION}/mcxray/${module}" COPYONLY)
endforeach ()
list(TRANSFORM mcxray_python_modules PREPEND "${CMAKE_BINARY_DIR}/${MCXRAY_PYTHON_DESTINATION}/mcxray/")
install(FILES "${CMAKE_BINARY_DIR}/${MCXRAY_PYTHON_DESTINATION}/mcxray/__init__.py" ${mcxray_python_modules}
  DESTINATION "${MCXRAY_PYTHON_DESTINATION}/mcxray")

# The extension modules find the libraries relative to themselves once installed.
file(RELATIVE_PATH mcxray_python_to_lib "/prefix/${MCXRAY_PYTHON_DESTINATION}/mcxray"
  "/prefix/${CMAKE_INSTALL_LIBDIR}")
foreach (library IN ITEMS MonteCarloXRayFiltersPython MonteCarloXRayRenderingPython MonteCarloXRayIOPython)
  set_target_properties(${library} PROPERTIES INSTALL_RPATH "$ORIGIN/${mcxray_python_to_lib}")
endforeach ()
