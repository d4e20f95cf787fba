#!/usr/bin/env bash
# README command (b): install what is needed, build, and run every test.
#
# 1. The full suite (every module, GPU tests on lavapipe, window tests under Xvfb) in build/,
#    after scripts/check-deps.py has proved that setup.sh installs every header, library and
#    program the build uses. LANTERN_REQUIRE_GPU=1: setup.sh always installs lavapipe and
#    Xvfb, so a GPU or window test that finds no Vulkan device or X server fails, never skips.
# 2. The engine's CPU suites again under ASan+UBSan built with clang (build-clang-asan/: the
#    second compiler) and TSan built with GCC (build-tsan/), with the Vulkan driver hidden:
#    their GPU tests skip, and the summary line says how many. Then the libFuzzer targets
#    of the clang build run for LANTERN_FUZZ_SECONDS each (default 60; 0 skips them).
#    Skip step 2 with LANTERN_TEST_SANITIZERS=0.
# Each run ends with one summary line: tests passed, failed and skipped, with the reasons.
#
# Environment: LANTERN_TEST_JOBS (parallel tests, default: cores).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
jobs="${LANTERN_TEST_JOBS:-$(nproc)}"

bash scripts/setup.sh

# ctest, then the one-line summary of its JUnit report; the status of ctest.
run_ctest() { # NAME BUILD_DIR [ctest args...]
    local name="$1" dir="$2" status=0
    shift 2
    ctest --test-dir "$dir" --output-on-failure -j "$jobs" --output-junit "$PWD/$dir/ctest-junit.xml" "$@" || status=$?
    python3 scripts/test-summary.py "$name" "$dir/ctest-junit.xml" || true
    return $status
}

echo "== build + test: full suite (build/)"
bash scripts/build.sh build -DLANTERN_BUILD_TESTS=ON
python3 scripts/check-deps.py build
LANTERN_REQUIRE_GPU=1 run_ctest "full suite" build

if [ "${LANTERN_TEST_SANITIZERS:-1}" != "0" ]; then
    # The engine's suites, with the Vulkan driver hidden: lavapipe runs LLVM-compiled shaders
    # on its own threads inside the process, which ASan slows tenfold and TSan reports as
    # races inside Mesa. The GPU tests then report themselves skipped; every CPU path (the
    # C++ reference backend included) still runs under the sanitizers. See docs/testing.md.
    # Anchored: ctest matches labels as regular expressions ('game' alone would take in
    # game_gpu and game_app, which run the game executable). Only these suites are built.
    labels='^(core|profile|jobs|ecs|scene|gpu_reflect|gi_reference|gi_gpu|texel|texel_gpu|systems|transport|bake|audio|game)$'
    export LANTERN_BUILD_TARGETS="lantern_core_tests lantern_profile_tests lantern_jobs_tests lantern_ecs_tests
        lantern_scene_tests lantern_gpu_reflect_tests lantern_gi_reference_tests lantern_gi_gpu_tests lantern_texel_tests
        lantern_texel_gpu_tests lantern_systems_tests
        lantern_transport_tests lantern_bake_tests lantern_audio_tests lantern_game_logic_tests"
    export VK_DRIVER_FILES=/nonexistent/lantern-sanitizer-run.json
    echo "== build + test: ASan+UBSan with clang (build-clang-asan/, labels $labels)"
    LANTERN_BUILD_TARGETS="$LANTERN_BUILD_TARGETS lantern-fuzz-scene lantern-fuzz-map lantern-fuzz-save lantern-fuzz-set lantern-fuzz-settings lantern-fuzz-tables lantern-fuzz-bake lantern-fuzz-spirv" \
        CC=clang CXX=clang++ bash scripts/build.sh build-clang-asan -DLANTERN_SANITIZE=address -DLANTERN_BUILD_BENCHMARKS=OFF
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        run_ctest "ASan+UBSan, clang (GPU hidden)" build-clang-asan -L "$labels"
    if [ "${LANTERN_FUZZ_SECONDS:-60}" != "0" ]; then
        echo "== fuzz: each parser for ${LANTERN_FUZZ_SECONDS:-60} s (build-clang-asan/)"
        bash scripts/fuzz.sh build-clang-asan "${LANTERN_FUZZ_SECONDS:-60}"
    fi
    echo "== build + test: TSan (build-tsan/, labels $labels)"
    bash scripts/build.sh build-tsan -DLANTERN_SANITIZE=thread -DLANTERN_BUILD_BENCHMARKS=OFF
    TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1 \
        run_ctest "TSan (GPU hidden)" build-tsan -L "$labels"
    unset VK_DRIVER_FILES LANTERN_BUILD_TARGETS
fi
echo "== all tests passed in $(( $(date +%s) - start )) s"
