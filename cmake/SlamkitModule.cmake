# Warnings and sanitizers for the project's own targets only. Everything here is PRIVATE (or
# build-tree only): none of it reaches the interface of the installed, exported targets.
function(slamkit_target_options target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wpedantic)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    # Without this the same seed gave another result under clang (the k-means, selection and
    # delayed-sampling tests' seeds landed elsewhere). It does not make clang's output GCC's:
    # GCC 12 fuses a * b + c into one FMA in C++ too (-ffp-contract=fast, its default outside
    # ISO C), wherever -march=native offers FMA, and clang with this flag never does. So figures
    # are reproducible for one compiler and one -march, bit for bit, not across them
    # (docs/architecture.md, "Reproducibility").
    target_compile_options(${target} PRIVATE -ffp-contract=off)
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ${SLAMKIT_UNITY_BUILD})
  if(SLAMKIT_NATIVE)
    # Eigen's kernels are where the EKF spends its time; with AVX2 and FMA the covariance
    # downdate runs 2-3x faster than with the SSE2 baseline. PRIVATE on purpose: an installed
    # package must not impose -march=native on the code that links it (build the package with
    # SLAMKIT_NATIVE=OFF to run it on any x86-64; slamkitConfig.cmake reports slamkit_NATIVE).
    target_compile_options(${target} PRIVATE ${SLAMKIT_NATIVE_FLAGS})
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      # GCC 12 reports these inside Eigen's AVX packet code on fixed-size objects (false
      # positives: the ASan/UBSan build checks the same code at run time).
      target_compile_options(${target} PRIVATE -Wno-array-bounds -Wno-maybe-uninitialized
                                               -Wno-stringop-overflow -Wno-stringop-overread)
    endif()
  endif()
  if(SLAMKIT_SANITIZE)
    # UBSan without its memory-access checks: ASan already stops at an access outside an array
    # or object or to freed memory and at a null dereference, and Eigen's assertions (on in this
    # build) check indices and the alignment of its fixed-size objects. They made a typical test
    # file compile about 1.7 times slower under clang 14. UBSan's own checks (integer overflow,
    # shifts, float-to-int casts of NaN and out-of-range values, division by zero, invalid bool
    # and enum loads, vptr, unreachable and missing returns) stay.
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
      -fno-sanitize-recover=all
      -fno-sanitize=alignment,null,pointer-overflow,object-size,bounds)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
  if(SLAMKIT_BUILD_FUZZ AND target IN_LIST SLAMKIT_FUZZ_COVERAGE_TARGETS)
    # Coverage feedback for libFuzzer from the modules the readers live in (the fuzz harnesses
    # call nothing else that parses); only the harnesses (fuzz/) link the fuzzer's main
    # (-fsanitize=fuzzer). Instrumenting every target made each compile about a fifth slower.
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# slamkit_module(NAME DEPS dep1 dep2 ...): static library slamkit_NAME, alias slamkit::NAME.
# Sources are listed by the caller with target_sources.
#
# The module is installed with no extra lines: the library (export set slamkitTargets, exported
# as slamkit::NAME, the same name as the in-tree alias, so code links the same way whether it
# uses the build tree or the installed package) and its headers include/slamkit/NAME/.
#
# A module with an option SLAMKIT_BUILD_<NAME> set to OFF (SLAMKIT_BUILD_REPORT) is disabled: the
# caller's target_sources still works, but slamkit_NAME is then an INTERFACE library that
# compiles nothing, there is no slamkit::NAME, and nothing of it is installed.
function(slamkit_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  string(TOUPPER "${name}" upper)
  if(DEFINED SLAMKIT_BUILD_${upper} AND NOT SLAMKIT_BUILD_${upper})
    add_library(slamkit_${name} INTERFACE)
    message(STATUS "slamkit: module ${name} disabled (SLAMKIT_BUILD_${upper}=OFF)")
    return()
  endif()
  add_library(slamkit_${name} STATIC)
  add_library(slamkit::${name} ALIAS slamkit_${name})
  set_target_properties(slamkit_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(slamkit_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(slamkit_${name} PUBLIC ${ARG_DEPS})
  slamkit_target_options(slamkit_${name})
  if(SLAMKIT_SANITIZE)
    target_link_options(slamkit_${name} INTERFACE $<BUILD_INTERFACE:-fsanitize=address,undefined>)
  endif()

  install(TARGETS slamkit_${name} EXPORT slamkitTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/include/slamkit/${name})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/slamkit/${name}
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/slamkit)
  endif()
  set_property(GLOBAL APPEND PROPERTY SLAMKIT_INSTALLED_MODULES ${name})
endfunction()

# One ctest test per test program (SLAMKIT_TEST_PER_PROGRAM), the programs with the most sources
# first (ctest starts the costliest first; a fresh tree has no timings yet) so the longest does
# not start last. A program of 16 sources or more runs as two halves (gtest's own sharding,
# which splits its cases deterministically), so that one program does not keep a core busy
# after the others are done.
function(slamkit_add_test_program name labels sources)
  list(LENGTH sources cost)
  set(shards 1)
  if(cost GREATER_EQUAL 16)
    set(shards 2)
  endif()
  math(EXPR last "${shards} - 1")
  foreach(shard RANGE ${last})
    set(test ${name})
    if(shards GREATER 1)
      set(test ${name}_${shard})
    endif()
    add_test(NAME ${test} COMMAND ${name} --gtest_brief=1)
    set_tests_properties(${test} PROPERTIES LABELS "${labels}" COST ${cost}
      ENVIRONMENT "GTEST_TOTAL_SHARDS=${shards};GTEST_SHARD_INDEX=${shard}")
  endforeach()
endfunction()

# slamkit_test(NAME SOURCES ... DEPS ... [LABELS ...] [NEEDS_CLI]): one gtest binary registered
# with ctest. The tests labelled `slow` or `release` are what scripts/test.sh builds and runs in
# the Release tree (target slamkit_release_tests, ctest -L 'slow|release'); every test but the
# slow ones runs in the sanitizer tree. Tests that run the `slamkit` program (NEEDS_CLI, and
# every test in tests/apps) see its path as SLAMKIT_CLI.
#
# A test that cannot be built in this configuration is skipped with a message: one that needs
# the CLI when SLAMKIT_BUILD_APPS=OFF, or one that links a disabled module (slamkit::report when
# SLAMKIT_BUILD_REPORT=OFF). NAME is then an empty INTERFACE library, so the caller's own
# follow-up lines (add_dependencies(NAME slamkit)) still configure.
function(slamkit_test)
  cmake_parse_arguments(ARG "NEEDS_CLI" "NAME" "SOURCES;DEPS;LABELS" ${ARGN})
  set(name ${ARG_NAME})
  if(CMAKE_CURRENT_SOURCE_DIR STREQUAL "${PROJECT_SOURCE_DIR}/tests/apps")
    set(ARG_NEEDS_CLI TRUE)
  endif()
  set(missing "")
  if(ARG_NEEDS_CLI AND NOT TARGET slamkit)
    set(missing "the slamkit program (SLAMKIT_BUILD_APPS=OFF)")
  endif()
  foreach(dep IN LISTS ARG_DEPS)
    if(dep MATCHES "^slamkit::" AND NOT TARGET ${dep})
      set(missing "${dep} (a disabled module)")
    endif()
  endforeach()
  if("slow" IN_LIST ARG_LABELS AND NOT SLAMKIT_BUILD_SLOW_TESTS)
    set(missing "a build with the slow tests (SLAMKIT_BUILD_SLOW_TESTS=OFF)")
  endif()
  if(missing)
    message(STATUS "slamkit: skipping test ${name}: it needs ${missing}")
    add_library(${name} INTERFACE)
    return()
  endif()

  add_executable(${name})
  target_sources(${name} PRIVATE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE
    SLAMKIT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SLAMKIT_DATASETS_DIR="${PROJECT_SOURCE_DIR}/../shared/datasets")
  if(ARG_NEEDS_CLI)
    target_compile_definitions(${name} PRIVATE SLAMKIT_CLI="$<TARGET_FILE:slamkit>")
    add_dependencies(${name} slamkit)
  endif()
  slamkit_target_options(${name})
  # Test files share helper names in their anonymous namespaces across a program; batches of 16
  # keep those apart whatever SLAMKIT_UNITY_BATCH_SIZE the libraries use.
  set_target_properties(${name} PROPERTIES UNITY_BUILD_BATCH_SIZE 16)
  if(SLAMKIT_SANITIZE)
    # Test code at -O0 in the sanitizer build (the library stays at -O1, where the tests spend
    # their time): it compiles in about two thirds of the time.
    target_compile_options(${name} PRIVATE -O0)
  elseif(ARG_NEEDS_CLI)
    # These run the program and read its files: their own code need not be fast, and at -O1
    # it compiles in two thirds of -O3's time.
    target_compile_options(${name} PRIVATE -O1)
  endif()
  if(SLAMKIT_TEST_PER_PROGRAM)
    slamkit_add_test_program(${name} "${ARG_LABELS}" "${ARG_SOURCES}")
  else()
    include(GoogleTest)
    gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS "${ARG_LABELS}")
  endif()
  if("slow" IN_LIST ARG_LABELS OR "release" IN_LIST ARG_LABELS)
    set_property(GLOBAL APPEND PROPERTY SLAMKIT_RELEASE_TESTS ${name})
  endif()
endfunction()
