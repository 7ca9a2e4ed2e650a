#!/usr/bin/env bash
# Runs the fast tests of a Release build (file readers and parsers, energies, Newton,
# adjoint, writers, CLI error paths; exceptions below) under valgrind's memcheck:
# invalid reads and writes, uses of uninitialised values and definite leaks fail the
# run. It needs no second build, so CI can afford it on every change; the full
# AddressSanitizer + UBSan build of every fast test is `make test-asan` (about 45 min
# on 2 cores, run before landing changes to memory-handling code).
#
# usage: scripts/memcheck.sh [BUILD_DIR]     (default build/release; JOBS=2 in parallel)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
jobs=${JOBS:-2}
command -v valgrind >/dev/null || { echo "memcheck: valgrind is not installed (scripts/install-deps.sh)" >&2; exit 2; }

# test executable : gtest filter. Every fast test (names ending in Slow are left out)
# except: CGAL-backed body operations (crop, local crop with its self-intersection
# checks, isotropic remeshing, distances — also the layouts' bone regions, whose skin
# weights are carried by closest point: valgrind ignores the rounding modes CGAL's
# interval arithmetic sets, so their exact predicates go wrong under it; so do the
# grading's joint check) and the few in-process runs that take over a second in Release
# (20-50x that under memcheck; the scene-pose tests read the 0.9 MB rig a dozen times,
# which the skin-weight tests already read under memcheck, as does the grading example;
# GradeCli writes scaled copies of the 13380-vertex bodies for 3-6 grading runs). CLI
# tests run the tightfit binary as a child process, which is not traced: those whose
# child optimizes for seconds (the pants example, the openings) are left out too, they
# would only add their run time.
# The output folder's kill test forks children that commit and kill themselves: under
# valgrind each child reports the parent's thread-pool memory as lost and exits with
# valgrind's error code, so it runs in `make test` only.
slow='*Slow*'
# Longest first (design ≈ 80 s, the output layers ≈ 55 s together under memcheck), so that the two jobs end together.
runs=(
  "tightfit_design_tests:*-$slow:AdjointSolve.*:AdjointPipelineSoftBody.*:PatternOptimizer.RecoversTheShapeOfAnotherPattern:*PatternOptimizerResume*soft*:SlidingObjective.PosesPull*:SlidingObjective.AdjointGradient*:AllPosesTerm.*:PinnedTractionRegularizer.*"
  "tightfit_scene_tests:*-$slow:SceneSpec.EveryExampleValidatesAgainstTheSchema:LayoutSceneSimulation.*:ScenePoses.*:SceneLayoutFileLoad.*"
  "tightfit_report_tests:*-$slow:PressureRegionStatistics.*"
  "tightfit_patterns_tests:*-$slow"
  "tightfit_grade_tests:*-$slow:GradeInputs.TheGradingExamples*:GradeInputs.JointsOutside*"
  "tightfit_app_tests:*-$slow:GradeCli.*:PantsExampleCli.*:OpeningsCli.*"
  "tightfit_garment_tests:*-$slow:Pants.*:LayoutBoneRegions.*:LayoutAnchorTransfer.*"
  "tightfit_solve_tests:*-$slow:RigidCylinderSleeveSliding.*:RigidCurvedBody.EllipticCylinder*"
  "tightfit_body_tests:*-$slow:BodyAcceptance.*:RemeshIsotropic.*:CropAndCap.*:LocalCrop.*:SurfaceDistance.*:Skinning.*"
  "tightfit_physics_tests:*-$slow"
  "tightfit_objectives_tests:*-$slow:PressureRegions.BoneRegions*"
  "tightfit_subdiv_tests:*-$slow"
  "tightfit_geometry_tests:*-$slow"
  "tightfit_common_tests:*-$slow:OutputDirectory.AKilledCommit*"
)

logs="$build/memcheck"
rm -rf "$logs"
mkdir -p "$logs"
export TIGHTFIT_DATA_DIR="$root/data" OPENBLAS_NUM_THREADS=1 TIGHTFIT_THREADS=2

run_one() {
  local exe=${1%%:*} filter=${1#*:}
  local log="$logs/$exe.log"
  # --run-libc-freeres=no: valgrind's call of glibc's __libc_freeres at exit can wait
  # forever on the dynamic loader's lock (seen: a test binary whose tests had all passed
  # hung in _dl_close under _vgnU_freeres); glibc's own buffers are not our leaks.
  if valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --run-libc-freeres=no \
      --show-leak-kinds=definite --errors-for-leak-kinds=definite --num-callers=30 \
      --suppressions="$root/tests/sanitizers/valgrind.supp" \
      "$build/tests/$exe" --gtest_filter="$filter" --gtest_brief=1 >"$log" 2>&1; then
    echo "memcheck: $exe ($filter) clean"
  else
    echo "memcheck: $exe ($filter) FAILED; log $log:" >&2
    tail -n 80 "$log" >&2
    return 1
  fi
}
export -f run_one
export logs build root
printf '%s\n' "${runs[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one "$@"' _ {}
