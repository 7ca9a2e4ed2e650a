# Every dependency is a Debian bookworm package installed by scripts/install-deps.sh.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CGAL REQUIRED)
find_package(Threads REQUIRED)
# The BLAS is OpenBLAS (pthread build, libopenblas0-pthread), which CHOLMOD reaches
# through Debian's libblas.so.3 alternative at run time (common/parallel.hpp).

# OpenSubdiv: bookworm's CMake config names a static library that is not shipped
# (docs/design.md §6), so the header and the shared CPU library are found directly.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/bfr/refinerSurfaceFactory.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY NAMES osdCPU REQUIRED)
add_library(tightfit_opensubdiv INTERFACE)
target_include_directories(tightfit_opensubdiv SYSTEM INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(tightfit_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})

# TetGen 1.5 (libtet1.5-dev), AGPL-3.
find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
find_library(TETGEN_LIBRARY NAMES tet REQUIRED)
add_library(tightfit_tetgen INTERFACE)
target_include_directories(tightfit_tetgen SYSTEM INTERFACE ${TETGEN_INCLUDE_DIR})
target_compile_definitions(tightfit_tetgen INTERFACE TETLIBRARY)
target_link_libraries(tightfit_tetgen INTERFACE ${TETGEN_LIBRARY})

# CHOLMOD (SuiteSparse 5.12) used through Eigen's CholmodSupport.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY NAMES cholmod REQUIRED)
find_library(SUITESPARSECONFIG_LIBRARY NAMES suitesparseconfig REQUIRED)
add_library(tightfit_cholmod INTERFACE)
target_include_directories(tightfit_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(tightfit_cholmod INTERFACE ${CHOLMOD_LIBRARY} ${SUITESPARSECONFIG_LIBRARY})

# CGAL 5.5 (header-only; GPL-3 for meshing, remeshing, parametrization).
add_library(tightfit_cgal INTERFACE)
target_link_libraries(tightfit_cgal INTERFACE CGAL::CGAL)

# cairo for PDF/SVG/PNG.
find_package(PkgConfig REQUIRED)
pkg_check_modules(CAIRO REQUIRED IMPORTED_TARGET cairo)
add_library(tightfit_cairo INTERFACE)
target_link_libraries(tightfit_cairo INTERFACE PkgConfig::CAIRO)

find_package(CLI11 QUIET)
if(NOT CLI11_FOUND)
  find_path(CLI11_INCLUDE_DIR CLI/CLI.hpp REQUIRED)
endif()

if(TIGHTFIT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(TIGHTFIT_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# The report viewer (report/template.html, report/viewer.js) and three.js from npm
# (pinned in report/package.json, installed into report/node_modules by
# scripts/install-deps.sh): write_report_html reads them at run time and inlines them
# into report.html. ReportOptions can point elsewhere.
set(TIGHTFIT_REPORT_DIR ${PROJECT_SOURCE_DIR}/report)
add_library(tightfit_report_assets INTERFACE)
target_compile_definitions(tightfit_report_assets INTERFACE
  TIGHTFIT_REPORT_VIEWER_DIR="${TIGHTFIT_REPORT_DIR}"
  TIGHTFIT_THREE_MODULE_JS="${TIGHTFIT_REPORT_DIR}/node_modules/three/build/three.module.js"
  TIGHTFIT_THREE_ORBIT_CONTROLS_JS="${TIGHTFIT_REPORT_DIR}/node_modules/three/examples/jsm/controls/OrbitControls.js")
