# Every dependency is a Debian 12 package (scripts/setup.sh installs them).
find_package(Threads REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(TBB REQUIRED)
find_package(Boost 1.74 REQUIRED)  # header-only parts: Boost.Math
find_package(PNG REQUIRED)
find_package(ZLIB REQUIRED)

# MathGL's own CMake config references optional front-ends (Qt, MPI) whose files Debian splits
# into other packages, so the core library is located directly.
find_path(MATHGL_INCLUDE_DIR mgl2/mgl_cf.h REQUIRED)
find_library(MATHGL_LIBRARY mgl REQUIRED)
add_library(slamkit_mathgl INTERFACE)
target_include_directories(slamkit_mathgl SYSTEM INTERFACE ${MATHGL_INCLUDE_DIR})
target_link_libraries(slamkit_mathgl INTERFACE ${MATHGL_LIBRARY})

if(SLAMKIT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(SLAMKIT_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
