# Every dependency is a Debian 12 package (scripts/setup.sh installs them). A package that the
# libraries' interface references (a module's DEPS) must also be found by
# cmake/slamkitConfig.cmake.in, for projects that use the installed package. CLI11 is for the
# slamkit program only.
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
find_package(Ceres REQUIRED)  # optim: sparse non-linear least squares (libceres-dev)
# io's ROS 1 bag reader (cmake/FindSlamkitRosbag.cmake): slamkit::rosbag.
find_package(SlamkitRosbag REQUIRED)

if(SLAMKIT_BUILD_REPORT)
  # MathGL, for the report module only (cmake/FindSlamkitMathGL.cmake): slamkit::mathgl.
  find_package(SlamkitMathGL REQUIRED)
  # The name src/report links.
  add_library(slamkit_mathgl ALIAS slamkit::mathgl)
endif()

if(SLAMKIT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(SLAMKIT_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
