# atlas_module(NAME <lib> [DEPS <targets...>])
#
# One folder, one module: every *.cc in the folder except *_test.cc, *_benchmark.cc,
# *_fuzzer.cc and *_main.cc forms the library <lib>; every *_test.cc is linked into one
# GoogleTest executable <lib>_test registered with ctest; every *_benchmark.cc into
# <lib>_benchmark; every *_fuzzer.cc becomes its own libFuzzer target when ATLAS_FUZZ is on.
# The robot build (ATLAS_ROBOT) makes the library only.
function(atlas_module)
  cmake_parse_arguments(M "" "NAME" "DEPS;TEST_DEPS" ${ARGN})
  file(GLOB all_cc CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cc)
  set(lib_cc "")
  set(test_cc "")
  set(bench_cc "")
  set(fuzz_cc "")
  foreach(f ${all_cc})
    if(f MATCHES "_test\\.cc$")
      list(APPEND test_cc ${f})
    elseif(f MATCHES "_benchmark\\.cc$")
      list(APPEND bench_cc ${f})
    elseif(f MATCHES "_fuzzer\\.cc$")
      list(APPEND fuzz_cc ${f})
    elseif(f MATCHES "_main\\.cc$")
    else()
      list(APPEND lib_cc ${f})
    endif()
  endforeach()
  if(lib_cc)
    add_library(${M_NAME} STATIC ${lib_cc})
    target_link_libraries(${M_NAME} PUBLIC ${M_DEPS} Eigen3::Eigen)
  else()
    add_library(${M_NAME} INTERFACE)
    target_link_libraries(${M_NAME} INTERFACE ${M_DEPS} Eigen3::Eigen)
  endif()
  if(test_cc AND NOT ATLAS_ROBOT)
    add_executable(${M_NAME}_test ${test_cc})
    target_link_libraries(${M_NAME}_test PRIVATE ${M_NAME} ${M_TEST_DEPS} GTest::gtest_main
                          GTest::gmock)
    if(ATLAS_TESTS_UNOPTIMISED)
      target_compile_options(${M_NAME}_test PRIVATE -O0)
    endif()
    if(ATLAS_UNITY_TESTS)
      set_target_properties(${M_NAME}_test PROPERTIES UNITY_BUILD ON
                            UNITY_BUILD_BATCH_SIZE ${ATLAS_UNITY_TESTS_BATCH})
    endif()
    gtest_discover_tests(${M_NAME}_test DISCOVERY_TIMEOUT 60
                         PROPERTIES LABELS unit ENVIRONMENT "LCM_DEFAULT_URL=memq://")
  endif()
  if(bench_cc AND ATLAS_BENCHMARKS)
    add_executable(${M_NAME}_benchmark ${bench_cc})
    target_link_libraries(${M_NAME}_benchmark PRIVATE ${M_NAME} ${M_TEST_DEPS}
                          benchmark::benchmark_main)
  endif()
  if(fuzz_cc AND ATLAS_FUZZ)
    foreach(f ${fuzz_cc})
      get_filename_component(fname ${f} NAME_WE)
      # The module's sources are compiled into the target so that they carry the fuzzer's
      # coverage instrumentation and the sanitizers (the plain library has neither).
      add_executable(${fname} ${f} ${lib_cc})
      target_compile_options(${fname} PRIVATE -fsanitize=fuzzer,address,undefined)
      target_link_options(${fname} PRIVATE -fsanitize=fuzzer,address,undefined)
      target_link_libraries(${fname} PRIVATE ${M_DEPS} Eigen3::Eigen)
      # A short run over the seed corpus (fuzz_corpus/ beside the source, read only; new inputs
      # go to the build tree) is part of ctest, label "fuzz".
      if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/fuzz_corpus)
        file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/${fname}_corpus)
        add_test(NAME ${fname}_short
                 COMMAND ${fname} -runs=20000 ${CMAKE_CURRENT_BINARY_DIR}/${fname}_corpus
                         ${CMAKE_CURRENT_SOURCE_DIR}/fuzz_corpus)
        set_tests_properties(${fname}_short PROPERTIES LABELS fuzz TIMEOUT 120)
      endif()
    endforeach()
  endif()
endfunction()

# Adds every child folder that has a CMakeLists.txt, so that modules can be added without
# editing their parent.
macro(atlas_add_child_modules)
  file(GLOB _children LIST_DIRECTORIES true RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}
       ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT _children)
  foreach(_c ${_children})
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${_c} AND
       EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${_c}/CMakeLists.txt)
      add_subdirectory(${_c})
    endif()
  endforeach()
endmacro()

# Ends the calling CMakeLists.txt in the robot build (ATLAS_ROBOT): for folders whose targets
# need GoogleTest, Ceres, Java or cairo (`needs`, printed).
macro(atlas_skip_in_robot_build needs)
  if(ATLAS_ROBOT)
    message(STATUS "robot build: ${CMAKE_CURRENT_SOURCE_DIR} skipped (needs ${needs})")
    return()
  endif()
endmacro()
