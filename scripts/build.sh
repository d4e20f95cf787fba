#!/usr/bin/env bash
# Configures and builds Lantern with Ninja.
#   scripts/build.sh [BUILD_DIR] [extra cmake -D options...]
# BUILD_DIR defaults to build/. Re-running only rebuilds what changed. LANTERN_BUILD_TARGETS
# (space-separated) builds only those targets and what they need.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir="${1:-build}"
shift || true
if [ ! -f "$build_dir/build.ninja" ]; then
    cmake -S . -B "$build_dir" -G Ninja "$@"
elif [ $# -gt 0 ]; then
    cmake "$build_dir" "$@"
fi
# shellcheck disable=SC2086 # the targets are meant to split
cmake --build "$build_dir" -j "$(nproc)" ${LANTERN_BUILD_TARGETS:+--target $LANTERN_BUILD_TARGETS}
