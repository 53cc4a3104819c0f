# The package files next to the exported targets (each module installs its own library and
# headers in slamkit_module()): `cmake --install BUILD --prefix DIR` makes DIR usable with
# find_package(slamkit) (CMAKE_PREFIX_PATH=DIR).
include(CMakePackageConfigHelpers)

set(SLAMKIT_CONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/slamkit)
get_property(SLAMKIT_INSTALLED_MODULES GLOBAL PROPERTY SLAMKIT_INSTALLED_MODULES)

install(EXPORT slamkitTargets NAMESPACE slamkit:: DESTINATION ${SLAMKIT_CONFIG_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/slamkitConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/slamkitConfig.cmake
                              INSTALL_DESTINATION ${SLAMKIT_CONFIG_DIR})
# 0.x: the API may still change between minor versions (the EkfSlam constructor is changing).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/slamkitConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
set(slamkit_config_files ${PROJECT_BINARY_DIR}/slamkitConfig.cmake
                         ${PROJECT_BINARY_DIR}/slamkitConfigVersion.cmake
                         ${PROJECT_SOURCE_DIR}/cmake/FindSlamkitRosbag.cmake)
if("report" IN_LIST SLAMKIT_INSTALLED_MODULES)
  list(APPEND slamkit_config_files ${PROJECT_SOURCE_DIR}/cmake/FindSlamkitMathGL.cmake)
endif()
install(FILES ${slamkit_config_files} DESTINATION ${SLAMKIT_CONFIG_DIR})
