# Precompiled headers (ATLAS_PCH, default OFF: -4.5 % CPU on the ASan+UBSan tree, below).
#
# Most translation units parse the same heavy headers: Eigen, and in tests GoogleTest/GoogleMock
# (about half of a test file's compile time). A few donor targets precompile them once per build
# tree, and every other C++ target of the project reuses one of them (REUSE_FROM):
#   atlas_pch_test_<n>: the standard headers below + Eigen/Dense + gtest + gmock, for every
#                       target that links GTest (unit tests, HIL test programs);
#   atlas_pch_lib_<n>:  the standard headers below + Eigen/Dense, for libraries, tools and
#                       benchmarks.
# libFuzzer targets (*_fuzzer, with their own -fsanitize flags) and targets that do not use
# Eigen get none.
#
# GCC builds with optimisation (RelWithDebInfo, Release) get none either: with the PCH, GCC 12 at
# -O2 reports false -Warray-bounds errors inside std::string's char_traits.h (inlined from
# `std::string(...) + "..."` in core/localmap/localmap_benchmark.cc and
# logs/carmen/carmen_line_test.cc) that it does not report without it, where the location is
# a system header. Nor do fuzz trees (ATLAS_FUZZ): scripts/test.sh builds only the fuzz targets
# and their few libraries there, and the donors cost more than they save (clang, 5 fuzzers:
# 87.4 s CPU with the PCH, 78.7 s without). So the PCH serves Debug (-O0) trees, e.g. the
# ASan+UBSan tree of scripts/test.sh, and full clang builds.
#
# A reused PCH is only valid when it was built with the flags and macros of the file that uses
# it. The donors are targets of the top directory, so they carry the global flags (-Wall -Wextra
# -Werror, build type, sanitizers ...); <n> numbers the distinct sets of
# compile options and definitions that a target receives from what it links (e.g. -pthread from
# LCM's pkg-config, which defines _REENTRANT), and the donor of that set carries the same ones.
# Definitions a target adds itself (ATLAS_FAKEDEV) or gets from a package found in a subfolder
# (glog's, through Ceres) are left out: GCC accepts a PCH whose headers do not use the file's
# extra macros, and refuses it otherwise.
# CMake compiles with -Winvalid-pch, so with -Werror a PCH that GCC refuses fails the build
# instead of being silently skipped.
#
# The PCH is force-included ahead of every source: a file that forgets an #include of one of
# these headers still compiles with ATLAS_PCH=ON. Build with -DATLAS_PCH=OFF to check that (in
# scripts/test.sh the release tree, which has no PCH, does).
#
# Gain (clean ASan+UBSan tree, same source, -j 2, both at load ~1.8): 1035.5 s CPU without
# (user 847.3 + sys 188.2, wall 8:51), 989.4 s with (user 726.1 + sys 263.3, wall 8:45): -4.5 %.
# Loading the ~180 MB PCH costs every file ~0.3-0.6 s of sys time, which eats most of the parse
# time saved; a test file with Eigen + gtest saves ~3 s (line_extraction_test.cc at -O2), a
# light file loses ~0.6 s.

set(ATLAS_PCH_STD_HEADERS
    <algorithm> <array> <atomic> <chrono> <cmath> <cstddef> <cstdint> <cstdio> <cstdlib>
    <cstring> <filesystem> <fstream> <functional> <limits> <map> <memory> <mutex> <numbers>
    <optional> <random> <span> <sstream> <string> <string_view> <thread> <utility> <vector>)

# Creates the donor targets and gives every C++ target under the top directory its PCH. Called
# once, at the end of the top CMakeLists.txt, when all targets exist.
function(atlas_precompile_headers)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
    message(STATUS "ATLAS_PCH: no precompiled headers for GCC with optimisation (false "
                   "-Warray-bounds, see cmake/atlas_pch.cmake)")
    return()
  endif()
  if(ATLAS_FUZZ)
    message(STATUS "ATLAS_PCH: no precompiled headers in a fuzz tree (it builds few files)")
    return()
  endif()
  set(empty_cc ${CMAKE_BINARY_DIR}/atlas_pch/empty.cc)
  file(CONFIGURE OUTPUT ${empty_cc} CONTENT "// Donor of the precompiled headers.\n")
  set(keys "")  # one entry per distinct set of usage requirements, "<kind>|<options>|<defs>"
  _atlas_targets_below(${CMAKE_SOURCE_DIR} targets)
  foreach(t ${targets})
    get_target_property(type ${t} TYPE)
    if(NOT type MATCHES "^(EXECUTABLE|STATIC_LIBRARY|SHARED_LIBRARY|OBJECT_LIBRARY)$" OR
       t MATCHES "^atlas_pch_" OR t MATCHES "_fuzzer$")
      continue()
    endif()
    _atlas_compile_usage(${t} opts defs uses_eigen)
    if(NOT uses_eigen)
      continue()
    endif()
    get_target_property(libs ${t} LINK_LIBRARIES)
    if(libs MATCHES "GTest::")
      set(kind test)
    else()
      set(kind lib)
    endif()
    string(REPLACE ";" " " key "${kind}|${opts}|${defs}")
    list(FIND keys "${key}" n)
    if(n EQUAL -1)
      list(LENGTH keys n)
      list(APPEND keys "${key}")
      set(donor atlas_pch_${kind}_${n})
      add_library(${donor} OBJECT ${empty_cc})
      target_compile_options(${donor} PRIVATE ${opts})
      target_compile_definitions(${donor} PRIVATE ${defs})
      target_link_libraries(${donor} PRIVATE Eigen3::Eigen)
      if(kind STREQUAL "test")
        target_link_libraries(${donor} PRIVATE GTest::gtest GTest::gmock)
        target_precompile_headers(${donor} PRIVATE ${ATLAS_PCH_STD_HEADERS} <Eigen/Dense>
                                  <gtest/gtest.h> <gmock/gmock.h>)
      else()
        target_precompile_headers(${donor} PRIVATE ${ATLAS_PCH_STD_HEADERS} <Eigen/Dense>)
      endif()
    endif()
    target_precompile_headers(${t} REUSE_FROM atlas_pch_${kind}_${n})
  endforeach()
endfunction()

# The compile options and definitions that reach target t's compile line from the targets it
# links (transitively; $<LINK_ONLY:...> entries carry none), sorted, and whether Eigen is among
# them.
function(_atlas_compile_usage t out_opts out_defs out_eigen)
  get_target_property(queue ${t} LINK_LIBRARIES)
  set(seen "")
  set(opts "")
  set(defs "")
  set(eigen FALSE)
  while(queue)
    list(POP_FRONT queue lib)
    if(NOT lib OR lib MATCHES "^\\$<" OR lib IN_LIST seen)
      continue()
    endif()
    if(NOT TARGET "${lib}")
      # pkg_check_modules' imported targets are visible only in their own directory; their
      # compile options are the cached <prefix>_CFLAGS_OTHER (e.g. LCM's -pthread).
      if(lib MATCHES "^PkgConfig::(.+)$")
        list(APPEND opts ${${CMAKE_MATCH_1}_CFLAGS_OTHER})
      endif()
      list(APPEND seen ${lib})
      continue()
    endif()
    list(APPEND seen ${lib})
    if(lib STREQUAL "Eigen3::Eigen")
      set(eigen TRUE)
    endif()
    get_target_property(o ${lib} INTERFACE_COMPILE_OPTIONS)
    get_target_property(d ${lib} INTERFACE_COMPILE_DEFINITIONS)
    get_target_property(l ${lib} INTERFACE_LINK_LIBRARIES)
    if(o)
      list(APPEND opts ${o})
    endif()
    if(d)
      list(APPEND defs ${d})
    endif()
    if(l)
      list(APPEND queue ${l})
    endif()
  endwhile()
  foreach(v opts defs)
    list(REMOVE_DUPLICATES ${v})
    list(SORT ${v})
  endforeach()
  set(${out_opts} "${opts}" PARENT_SCOPE)
  set(${out_defs} "${defs}" PARENT_SCOPE)
  set(${out_eigen} ${eigen} PARENT_SCOPE)
endfunction()

function(_atlas_targets_below dir out)
  get_property(found DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(s ${subdirs})
    _atlas_targets_below(${s} below)
    list(APPEND found ${below})
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()
