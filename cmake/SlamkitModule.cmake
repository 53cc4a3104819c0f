# Warnings and sanitizers for the project's own targets only.
function(slamkit_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wpedantic)
  if(SLAMKIT_NATIVE)
    # Eigen's kernels are where the EKF spends its time; with AVX2/AVX-512 and FMA the covariance
    # downdate runs 2-3x faster than with the SSE2 baseline.
    target_compile_options(${target} PRIVATE -march=native)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      # GCC 12 reports these inside Eigen's AVX packet code on fixed-size objects (false
      # positives: the ASan/UBSan build checks the same code at run time).
      target_compile_options(${target} PRIVATE -Wno-array-bounds -Wno-maybe-uninitialized
                                               -Wno-stringop-overflow -Wno-stringop-overread)
    endif()
  endif()
  if(SLAMKIT_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                             -fno-sanitize-recover=all)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# slamkit_module(NAME DEPS dep1 dep2 ...): static library slamkit_NAME, alias slamkit::NAME.
# Sources are listed by the caller with target_sources.
function(slamkit_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  add_library(slamkit_${name} STATIC)
  add_library(slamkit::${name} ALIAS slamkit_${name})
  target_include_directories(slamkit_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(slamkit_${name} PUBLIC ${ARG_DEPS})
  slamkit_target_options(slamkit_${name})
  if(SLAMKIT_SANITIZE)
    target_link_options(slamkit_${name} INTERFACE -fsanitize=address,undefined)
  endif()
endfunction()

# slamkit_test(NAME SOURCES ... DEPS ... [LABELS ...]): one gtest binary registered with ctest.
function(slamkit_test)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPS;LABELS" ${ARGN})
  set(name ${ARG_NAME})
  add_executable(${name})
  target_sources(${name} PRIVATE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE
    SLAMKIT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SLAMKIT_DATASETS_DIR="${PROJECT_SOURCE_DIR}/../shared/datasets"
    SLAMKIT_CLI="$<TARGET_FILE:slamkit>")
  slamkit_target_options(${name})
  include(GoogleTest)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${ARG_LABELS}")
endfunction()
