#!/usr/bin/env bash
# The test suite under the sanitizers (issue 18): every report is an error.
#
#   scripts/sanitize.sh [address|thread|all]     (default: address; CI runs all)
#
# address: the whole suite built with -fsanitize=address,undefined in build-asan.
# thread:  the pipeline, navigator and rig suites (the executor's threads, the trials' parallel
#          journeys) built with -fsanitize=thread in build-tsan, against a oneTBB built with TSan from
#          Debian's source of the installed version (scripts/sanitizers/onetbb-tsan.sh): Debian's
#          libtbb is not instrumented, and every hand-over through a task would look like a race.
# Both trees are built with -O1 -g (fast enough to run, exact enough to point at a line) through
# ccache when it is there, so a second run on the same machine recompiles only what changed.
# Run scripts/setup.sh first (CI does: the README's test command before this).
set -euo pipefail
cd "$(dirname "$0")/.."
what="${1:-address}"
case "$what" in address | thread | all) ;; *)
  echo "scripts/sanitize.sh: unknown sanitizer '$what' (address, thread or all)" >&2
  exit 2
  ;;
esac

launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Trees in different folders share the cache: paths are made relative to the checkout.
  export CCACHE_BASEDIR="$PWD"
fi
jobs="$(nproc)"
suppressions="$PWD/scripts/sanitizers"

configure() {  # folder, sanitizers, more cmake options
  cmake -S . -B "$1" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DNEOPIPE_SANITIZE="$2" "${launcher[@]}" "${@:3}" > /dev/null
}

if [[ "$what" == address || "$what" == all ]]; then
  echo "== address,undefined: the whole suite (build-asan)"
  configure build-asan address,undefined -DNEOPIPE_UNITY_BUILD=ON
  cmake --build build-asan -j "$jobs"
  export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=1"
  export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$suppressions/ubsan.supp"
  export LSAN_OPTIONS="suppressions=$suppressions/lsan.supp"
  # Skipped, the only two: the rate guards (NavigationRates.*: 5,000 simulated journeys, over 30 min
  # under ASan) and the planner's brute force over every simple step sequence (8 min). The code they
  # run runs under ASan in the shorter Rig, Journeys, NavCli and MapMaker tests.
  ctest --test-dir build-asan --output-on-failure -j "$jobs" --timeout 1800 \
    -E '^(NavigationRates\..*|MapMaker\.ShortestRouteEqualsBruteForceOverAllSimpleStepSequences)$'

  unset ASAN_OPTIONS UBSAN_OPTIONS LSAN_OPTIONS
fi

if [[ "$what" == thread || "$what" == all ]]; then
  echo "== thread: the pipeline, navigator and rig suites (build-tsan)"
  scripts/sanitizers/onetbb-tsan.sh "$PWD/build-tsan/onetbb"
  configure build-tsan thread -DTBB_DIR="$PWD/build-tsan/onetbb/lib/cmake/TBB"
  cmake --build build-tsan -j "$jobs" --target neopipe_pipeline_tests neopipe_navigator_tests neopipe_rig_tests
  # The binaries find the instrumented libtbb through their run path; say so if they do not.
  # ldd's output is read whole first: `grep -q` stops at the first match, and under pipefail the
  # SIGPIPE ldd then gets would fail the check (it did on CI once the binaries linked more libraries).
  linked="$(ldd build-tsan/tests/neopipe_pipeline_tests)"
  if [[ "$linked" != *"build-tsan/onetbb/lib/libtbb"* ]]; then
    echo "scripts/sanitize.sh: build-tsan does not link the TSan build of oneTBB" >&2
    exit 1
  fi
  export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$suppressions/tsan.supp"
  # Each binary runs whole (one process): the threads of one test meet the pools another left.
  for suite in pipeline navigator; do
    echo "-- neopipe_${suite}_tests"
    "build-tsan/tests/neopipe_${suite}_tests" --gtest_brief=1
  done
  # Skipped: the rate guards (NavigationRates.*) run thousands of journeys, an hour under TSan's
  # slowdown; the parallel trials they share code with run in the other Rig tests (the same
  # outcomes for 1 and 2 threads).
  echo "-- neopipe_rig_tests (without NavigationRates.*)"
  build-tsan/tests/neopipe_rig_tests --gtest_brief=1 --gtest_filter='-NavigationRates.*'

  unset TSAN_OPTIONS
fi
echo "sanitizers: clean"
