#!/usr/bin/env bash
# README command (a): install what is needed, build, and run the main job: the sandbox game.
# With a display it opens the game window; without one it plays the scripted headless demo
# (900 frames), writing screenshots, timings.json, profile.txt and a Chrome trace to
# out/demo/ and printing the frame-time percentiles. Extra arguments go to the game
# (`bash scripts/run.sh --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh build -DLANTERN_BUILD_TESTS=OFF -DLANTERN_BUILD_BENCHMARKS=OFF
mkdir -p out
exec ./build/game/lantern --out out/demo "$@"
