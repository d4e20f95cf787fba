#!/usr/bin/env bash
# README command (a): install what is needed, build, and run the main job.
# Until the sandbox game lands, the main job is the engine demo: 100k agents simulated
# by ECS systems on the job graph; it prints the profiler report and writes a Chrome
# trace to out/demo_trace.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build -DLANTERN_BUILD_TESTS=OFF -DLANTERN_BUILD_BENCHMARKS=OFF
mkdir -p out
exec ./build/tools/demo/lantern-demo --frames 300 --trace out/demo_trace.json "$@"
