# CMake package files, so that another project can:
#   find_package(MonteCarloXRay REQUIRED COMPONENTS Filters)
#   target_link_libraries(app PRIVATE MonteCarloXRay::Filters)
include(CMakePackageConfigHelpers)

set(mcxray_cmake_destination "${CMAKE_INSTALL_LIBDIR}/cmake/MonteCarloXRay")

# Lets the package find the same VTK modules it was built with.
vtk_module_export_find_packages(
  CMAKE_DESTINATION "${mcxray_cmake_destination}"
  FILE_NAME         "MonteCarloXRay-vtk-module-find-packages.cmake"
  MODULES           ${mcxray_modules})

configure_package_config_file(
  "${CMAKE_CURRENT_LIST_DIR}/MonteCarloXRayConfig.cmake.in"
  "${CMAKE_BINARY_DIR}/${mcxray_cmake_destination}/MonteCarloXRayConfig.cmake"
  INSTALL_DESTINATION "${mcxray_cmake_destination}")
write_basic_package_version_file(
  "${CMAKE_BINARY_DIR}/${mcxray_cmake_destination}/MonteCarloXRayConfigVersion.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)

install(
  FILES
    "${CMAKE_BINARY_DIR}/${mcxray_cmake_destination}/MonteCarloXRayConfig.cmake"
    "${CMAKE_BINARY_DIR}/${mcxray_cmake_destination}/MonteCarloXRayConfigVersion.cmake"
  DESTINATION "${mcxray_cmake_destination}"
  COMPONENT   development)
