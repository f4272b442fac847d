# One static library per pipeline stage, built from every .cpp in its folder.
# The link graph between stages is the dependency picture of ARCHITECTURE.md:
# a stage can only include what it links, so an arrow pointing the wrong way fails to build.
function(xparam_stage name dir)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
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
  gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
                       PROPERTIES ENVIRONMENT "XPARAM_SOURCE_DIR=${PROJECT_SOURCE_DIR}" LABELS "${label}"
                       DISCOVERY_TIMEOUT 60)
endfunction()
