# Finds MathGL's core library (Debian: libmgl-dev) and defines the imported target
# slamkit::mathgl. Used by the build and, installed next to slamkitConfig.cmake, by projects that
# use slamkit::report.
#
# MathGL's own CMake config references optional front-ends (Qt, MPI) whose files Debian splits
# into other packages, so the core library is located directly.
find_path(MATHGL_INCLUDE_DIR mgl2/mgl_cf.h)
find_library(MATHGL_LIBRARY mgl)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SlamkitMathGL REQUIRED_VARS MATHGL_LIBRARY MATHGL_INCLUDE_DIR)
if(SlamkitMathGL_FOUND AND NOT TARGET slamkit::mathgl)
  add_library(slamkit::mathgl INTERFACE IMPORTED)
  target_include_directories(slamkit::mathgl SYSTEM INTERFACE ${MATHGL_INCLUDE_DIR})
  target_link_libraries(slamkit::mathgl INTERFACE ${MATHGL_LIBRARY})
endif()
mark_as_advanced(MATHGL_INCLUDE_DIR MATHGL_LIBRARY)
