#!/usr/bin/env bash
# The whole ctest suite on a busy machine: one busy loop per core competes with it for the
# whole run. Proves that no test waits on time instead of a condition (docs/testing.md).
#
#   bash scripts/test-under-load.sh [RUNS]      (default 3 runs in a row; all must pass)
#
# Installs and builds like scripts/test.sh (build/), then runs the suite once on the quiet
# machine and RUNS times under load, with LANTERN_REQUIRE_GPU=1 as the test command has it,
# and prints the wall time of each run against the quiet one. Exit status: that of the first
# failing run, else 0. LANTERN_TEST_JOBS sets the parallel tests (default: cores).
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-3}"
if ! [[ "$runs" =~ ^[1-9][0-9]*$ ]]; then
    echo "test-under-load: RUNS must be a positive integer (got '$runs')" >&2
    exit 2
fi
jobs="${LANTERN_TEST_JOBS:-$(nproc)}"

bash scripts/setup.sh
bash scripts/build.sh build -DLANTERN_BUILD_TESTS=ON

busy=()
stop_load() {
    if [ ${#busy[@]} -gt 0 ]; then
        kill "${busy[@]}" 2>/dev/null || true
        wait "${busy[@]}" 2>/dev/null || true
    fi
    busy=()
}
trap stop_load EXIT

# One ctest run; prints its summary line and leaves its wall seconds in $seconds.
run_suite() { # NAME
    local name="$1" start status=0
    start=$(date +%s)
    LANTERN_REQUIRE_GPU=1 ctest --test-dir build --output-on-failure -j "$jobs" \
        --output-junit "$PWD/build/ctest-junit-load.xml" > "build/test-under-load.log" 2>&1 || status=$?
    seconds=$(( $(date +%s) - start ))
    python3 scripts/test-summary.py "$name" build/ctest-junit-load.xml || true
    if [ $status -ne 0 ]; then
        grep -E "\*\*\*Failed|Failed  |Timeout|Exception" build/test-under-load.log | head -20 >&2 || true
        echo "test-under-load: $name failed after $seconds s (log: build/test-under-load.log)" >&2
    fi
    return $status
}

echo "== quiet run"
run_suite "quiet"
quiet=$seconds
times=()
for run in $(seq 1 "$runs"); do
    for _ in $(seq 1 "$(nproc)"); do
        ( while :; do :; done ) &
        busy+=($!)
    done
    echo "== run $run of $runs under load: ${#busy[@]} busy loops on $(nproc) cores"
    run_suite "under load $run/$runs"
    times+=("$seconds")
    stop_load
done
echo "== wall time: quiet $quiet s; under load: ${times[*]} s (one busy loop per core)"
