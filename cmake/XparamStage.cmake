# Third-party headers nearly every file includes, parsed once instead of once per file
# (target_precompile_headers). Parsing them is 8-10 s of each file's compile on the 2-core CI
# machine (tests/io/anchor_reader_test.cpp: 24 s without them precompiled, 19 s with). Targets of
# one `group` compile with the same flags, so the group's first target builds the precompiled
# header and the others reuse it; a target with flags of its own (CGAL's) is a group of its own.
# Turn the option off to check that every file includes what it uses.
option(XPARAM_PRECOMPILE_HEADERS "Precompile the heavy third-party headers" ON)
set(XPARAM_COMMON_HEADERS <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh> <Eigen/Dense> <Eigen/Sparse>
    <algorithm> <array> <cmath> <filesystem> <functional> <map> <memory> <optional> <set> <string>
    <unordered_map> <vector>)
function(xparam_precompile_headers target group)
  if(NOT XPARAM_PRECOMPILE_HEADERS)
    return()
  endif()
  get_property(owner GLOBAL PROPERTY XPARAM_PRECOMPILED_HEADERS_OF_${group})
  if(owner)
    target_precompile_headers(${target} REUSE_FROM ${owner})
  else()
    target_precompile_headers(${target} PRIVATE ${XPARAM_COMMON_HEADERS} ${ARGN})
    set_property(GLOBAL PROPERTY XPARAM_PRECOMPILED_HEADERS_OF_${group} ${target})
  endif()
endfunction()

# The targets whose speed is not the pipeline's (the tests, the program's command line and outputs,
# the batch driver, the benchmarks' set-up) compile their sources four to a translation unit: the
# headers (GoogleTest, CLI11, nlohmann-json, Eigen, OpenMesh) are parsed and their templates
# instantiated once per four files. The Release build of everything: 15.5 -> 11.4 minutes on the
# 2-core CI machine. The stages compile file by file: built in batches, the pipeline ran 2-5%
# slower (inlined differently; the man onto the edge-flipped man, best of 8: 2.11 against 2.00 s).
# Names at namespace scope in a batched .cpp, anonymous ones included, are distinct within its
# folder.
function(xparam_unity_build target)
  if(XPARAM_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 4)
  endif()
endfunction()

# One static library per pipeline stage, built from every .cpp in its folder.
# The link graph between stages is the dependency picture of ARCHITECTURE.md:
# a stage can only include what it links, so an arrow pointing the wrong way fails to build.
# OWN_COMPILE_FLAGS: the stage adds flags of its own (a private dependency's definitions), so it
# cannot share the other stages' precompiled header.
function(xparam_stage name dir)
  cmake_parse_arguments(ARG "OWN_COMPILE_FLAGS" "" "DEPENDS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/*.cpp)
  if(NOT sources)
    # A stage with headers only (or none yet) still carries its include paths and dependencies.
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}
                                                 ${PROJECT_BINARY_DIR}/generated)
    target_link_libraries(${name} INTERFACE ${ARG_DEPENDS})
    return()
  endif()
  add_library(${name} STATIC ${sources})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}
                                            ${PROJECT_BINARY_DIR}/generated)
  target_link_libraries(${name} PUBLIC ${ARG_DEPENDS} PRIVATE xparam_compile_options)
  if(ARG_OWN_COMPILE_FLAGS)
    xparam_precompile_headers(${name} ${name})
  else()
    xparam_precompile_headers(${name} stages)
  endif()
endfunction()

# GoogleTest executables of a test folder, one per label: `name` from its *_test.cpp files (label
# `fast`), `name`_slow from its *_slow_test.cpp files (label `slow`: long on the bundled data, e.g.
# a whole pair mapped twice to compare thread counts), and `name`_real_data from its
# *_real_data_test.cpp files (label `real_data`: long cases on ../shared/data). A pass leaves
# labels out with `ctest -LE`, or leaves the long executables unbuilt with XPARAM_BUILD_LONG_TESTS=OFF:
# the sanitizer pass builds and runs only `fast`.
option(XPARAM_BUILD_LONG_TESTS "Build the tests labelled slow and real_data" ON)
function(xparam_test_folder name dir)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${dir}/*_test.cpp)
  foreach(label slow real_data)
    set(${label}_sources ${sources})
    list(FILTER ${label}_sources INCLUDE REGEX "_${label}_test\\.cpp$")
    list(FILTER sources EXCLUDE REGEX "_${label}_test\\.cpp$")
  endforeach()
  if(sources)
    xparam_test_executable(${name} fast ${sources} DEPENDS ${ARG_DEPENDS})
  endif()
  foreach(label slow real_data)
    if(${label}_sources AND XPARAM_BUILD_LONG_TESTS)
      xparam_test_executable(${name}_${label} ${label} ${${label}_sources} DEPENDS ${ARG_DEPENDS})
    endif()
  endforeach()
endfunction()

function(xparam_test_executable name label)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  add_executable(${name} ${ARG_UNPARSED_ARGUMENTS})
  target_link_libraries(${name} PRIVATE ${ARG_DEPENDS} xparam_test_support GTest::gtest_main
                                        xparam_compile_options)
  xparam_precompile_headers(${name} tests <gtest/gtest.h> <nlohmann/json.hpp>)
  xparam_unity_build(${name})
  # A test's own code is set-up and assertions; the library it calls keeps the build's flags. In
  # Release -O1 compiles it in half the time of -O3; under the sanitizers -O0 in half the time of
  # -O1 with their instrumentation (tests/io/anchor_reader_test.cpp: 31 -> 16 s).
  if(XPARAM_SANITIZE)
    target_compile_options(${name} PRIVATE -O0)
  else()
    target_compile_options(${name} PRIVATE $<$<CONFIG:Release>:-O1>)
  endif()
  gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       PROPERTIES ENVIRONMENT "XPARAM_SOURCE_DIR=${PROJECT_SOURCE_DIR}" LABELS "${label}"
                       DISCOVERY_TIMEOUT 60)
endfunction()
