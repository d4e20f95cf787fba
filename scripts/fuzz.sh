#!/usr/bin/env bash
# Runs Lantern's libFuzzer targets (tests/fuzz) for SECONDS each and reports how many inputs
# each ran. The targets come from the clang ASan+UBSan build (test.sh builds it as
# build-clang-asan/; docs/testing.md, "Fuzzing"):
#
#   scripts/fuzz.sh [BUILD_DIR] [SECONDS] [TARGET...]    (defaults: build-clang-asan 60, all eight)
#
# Each target starts from its seed corpus (tests/fuzz/corpus/<target>/, plus tests/golden for
# scenes) and keeps what it learns in BUILD_DIR/fuzz-corpus/<target>/ (outside the tree).
# A finding (a crash, a sanitizer report, a leak, an input over the memory limit or a hang
# past the timeout) ends that target's run and the script's with exit 1 (the other targets
# run their time); libFuzzer's reproducer is kept in BUILD_DIR/fuzz-findings/: copy it into
# the seed corpus as a regression input once fixed.
#
# Targets run side by side, LANTERN_FUZZ_JOBS at a time (default: the cores; each libFuzzer
# process is one thread), so each still fuzzes for SECONDS, on a core of its own.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-clang-asan}"
seconds="${2:-60}"
shift $(( $# > 2 ? 2 : $# ))
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene map save set settings tables bake spirv)

findings="$build/fuzz-findings"
mkdir -p "$findings"
for t in "${targets[@]}"; do # every target present before any starts
    exe="$build/tests/fuzz/lantern-fuzz-$t"
    if [ ! -x "$exe" ]; then
        echo "fuzz: $exe is missing (configure $build with CXX=clang++ -DLANTERN_SANITIZE=address)" >&2
        exit 2
    fi
done

# One target for SECONDS; its line on stdout, or its finding on stderr and status 1.
fuzz_one() {
    local t="$1" exe="$build/tests/fuzz/lantern-fuzz-$1" corpus="$build/fuzz-corpus/$1" log="$build/fuzz-$1.log" runs
    mkdir -p "$corpus"
    local seeds=("tests/fuzz/corpus/$t")
    [ "$t" = scene ] && seeds+=("tests/golden")
    # -rss_limit_mb/-malloc_limit_mb: an input that makes a parser allocate over 2 GiB is a
    # finding (the loaders must refuse it first). -timeout: one input running 10 s is a hang.
    if ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536 \
        -print_final_stats=1 -artifact_prefix="$findings/$t-" "$corpus" "${seeds[@]}" > "$log" 2>&1; then
        runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
        echo "fuzz: $t: $runs inputs in ${seconds} s, no finding"
    else
        echo "fuzz: $t: FINDING (log: $log; reproducer in $findings/)" >&2
        grep -E "ERROR|SUMMARY|runtime error|Test unit written" "$log" | head -5 >&2 || true
        return 1
    fi
}

parallel="${LANTERN_FUZZ_JOBS:-$(nproc)}"
[ "$parallel" -ge 1 ] 2>/dev/null || parallel=1
# Waited for by pid, oldest first (every target runs SECONDS, so the oldest ends first):
# `wait -n` loses the status of a job that ended before it is called.
status=0
pids=()
for t in "${targets[@]}"; do
    if [ "${#pids[@]}" -ge "$parallel" ]; then
        wait "${pids[0]}" || status=1
        pids=("${pids[@]:1}")
    fi
    fuzz_one "$t" &
    pids+=("$!")
done
for pid in "${pids[@]}"; do wait "$pid" || status=1; done
exit $status
