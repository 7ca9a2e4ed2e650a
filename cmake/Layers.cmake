# Project-wide warnings and sanitizer flags, applied to every tightfit target.
add_library(tightfit_options INTERFACE)
target_compile_options(tightfit_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow
  -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual -Wno-unused-parameter)
if(TIGHTFIT_WERROR)
  target_compile_options(tightfit_options INTERFACE -Werror)
endif()
if(TIGHTFIT_SANITIZE)
  target_compile_options(tightfit_options INTERFACE -fsanitize=address,undefined
    -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(tightfit_options INTERFACE -fsanitize=address,undefined)
endif()

# tightfit_add_layer(NAME DEPS ...) builds src/tightfit/NAME/*.cpp into the library
# tightfit_NAME (an INTERFACE library while the layer has no sources yet) and
# tests/NAME/*_test.cpp into the test executable tightfit_NAME_tests.
set(TIGHTFIT_LAYERS "" CACHE INTERNAL "")
function(tightfit_add_layer name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/tightfit/${name}/*.cpp)
  if(sources)
    add_library(tightfit_${name} STATIC ${sources})
    target_include_directories(tightfit_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(tightfit_${name} PUBLIC ${ARG_DEPS} tightfit_options)
  else()
    add_library(tightfit_${name} INTERFACE)
    target_include_directories(tightfit_${name} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(tightfit_${name} INTERFACE ${ARG_DEPS} tightfit_options)
  endif()
  set(TIGHTFIT_LAYERS ${TIGHTFIT_LAYERS} ${name} CACHE INTERNAL "")
endfunction()
