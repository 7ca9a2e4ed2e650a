# Project-wide warnings and sanitizer flags, applied to every tightfit target.
add_library(tightfit_options INTERFACE)
target_compile_options(tightfit_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wno-unused-parameter)
# CGAL needs -frounding-math (its interval arithmetic changes the rounding mode), and
# every layer from geometry up links CGAL; giving it to every target keeps the compile
# flags of all layers alike, so that they can share one precompiled header (below).
target_compile_options(tightfit_options INTERFACE -frounding-math)
if(TIGHTFIT_WERROR)
  target_compile_options(tightfit_options INTERFACE -Werror)
endif()
if(TIGHTFIT_BUILD_FUZZERS)
  # Coverage instrumentation for libFuzzer in every library (fuzz/CMakeLists.txt links
  # the fuzzers' main); clang only.
  target_compile_options(tightfit_options INTERFACE -fsanitize=fuzzer-no-link)
endif()
if(TIGHTFIT_SANITIZE)
  target_compile_options(tightfit_options INTERFACE -fsanitize=address,undefined
    -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(tightfit_options INTERFACE -fsanitize=address,undefined)
endif()

# Precompiled headers: the standard, Eigen and JSON headers that nearly every source
# file parses (about 2 s of CPU per file otherwise). A precompiled header costs 11-16 s
# to build, so the targets share them: every library layer uses the one of
# tightfit_common, every test executable the one of the first test executable (which
# adds GoogleTest); the CLI has its own (which adds CLI11). Off with -DTIGHTFIT_PCH=OFF
# (e.g. when a compiler cache is used).
option(TIGHTFIT_PCH "Precompile the common standard/Eigen/JSON headers" ON)
set(TIGHTFIT_PCH_HEADERS <algorithm> <array> <cmath> <filesystem> <functional> <map>
  <memory> <optional> <string> <vector> <Eigen/Core> <Eigen/Geometry> <Eigen/SparseCore>
  <nlohmann/json.hpp>)
# tightfit_precompile(TARGET [HEADER ...]): TARGET gets its own precompiled header with
# the common headers and HEADER ...
function(tightfit_precompile target)
  if(TIGHTFIT_PCH)
    target_precompile_headers(${target} PRIVATE ${TIGHTFIT_PCH_HEADERS} ${ARGN})
  endif()
endfunction()
# tightfit_share_precompiled(TARGET FROM): TARGET uses the precompiled header of FROM
# (same compile options; definitions may differ when the headers do not use them).
function(tightfit_share_precompiled target from)
  if(TIGHTFIT_PCH)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()

# Unity build: each library layer and the CLI compile their sources in batches of eight
# (CMake's UNITY_BUILD), which parses the CGAL, Eigen and JSON templates they share once
# per batch instead of once per file. Helpers in anonymous namespaces must therefore have
# names unique within their layer, and a class member may not have an anonymous-namespace
# type (CONTRIBUTING.md). Off with -DTIGHTFIT_UNITY_BUILD=OFF (one object per source:
# faster incremental rebuilds while editing one file).
option(TIGHTFIT_UNITY_BUILD "Compile the library layers and the CLI in batches of 8" ON)
function(tightfit_unity target)
  if(TIGHTFIT_UNITY_BUILD)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()

# tightfit_cgal_sources_first(LIST): the sources of LIST that include CGAL headers first,
# so that a unity build puts them in the same batches: they share the parsing and the
# instantiation of CGAL's kernel and Surface_mesh templates (the body layer's five: 78 s
# of compile CPU in one batch with three other sources, 117 s apart). Read at configure
# time: a source that starts or stops including CGAL is moved at the next configure.
function(tightfit_cgal_sources_first list_var)
  set(cgal_users "")
  set(others "")
  foreach(source IN LISTS ${list_var})
    file(STRINGS ${source} cgal_includes REGEX "^#include <CGAL/" LIMIT_COUNT 1)
    if(cgal_includes)
      list(APPEND cgal_users ${source})
    else()
      list(APPEND others ${source})
    endif()
  endforeach()
  set(${list_var} ${cgal_users} ${others} PARENT_SCOPE)
endfunction()

# tightfit_add_layer(NAME DEPS ...) builds src/tightfit/NAME/*.cpp into the library
# tightfit_NAME (an INTERFACE library while the layer has no sources yet) and
# tests/NAME/*_test.cpp into the test executable tightfit_NAME_tests.
set(TIGHTFIT_LAYERS "" CACHE INTERNAL "")
function(tightfit_add_layer name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tightfit/${name}/*.cpp)
  tightfit_cgal_sources_first(sources)
  if(sources)
    add_library(tightfit_${name} STATIC ${sources})
    target_include_directories(tightfit_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(tightfit_${name} PUBLIC ${ARG_DEPS} tightfit_options nlohmann_json::nlohmann_json)
    tightfit_unity(tightfit_${name})
    if(name STREQUAL "common")
      tightfit_precompile(tightfit_common)
    else()
      tightfit_share_precompiled(tightfit_${name} tightfit_common)
    endif()
  else()
    add_library(tightfit_${name} INTERFACE)
    target_include_directories(tightfit_${name} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(tightfit_${name} INTERFACE ${ARG_DEPS} tightfit_options)
  endif()
  set(TIGHTFIT_LAYERS ${TIGHTFIT_LAYERS} ${name} CACHE INTERNAL "")
endfunction()
