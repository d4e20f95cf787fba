#!/usr/bin/env bash
# Regenerates the picture of the game's frame schedule in docs/frame.md: the game writes its
# schedule as Graphviz DOT (--schedule) after one headless frame, Graphviz (Debian's
# graphviz, installed by scripts/setup.sh) draws it. The game_app test compares the DOT with
# docs/frame/schedule.dot, so run this when systems or their declared access change, and
# explain any new ambiguity in docs/frame.md.
#   bash scripts/update-schedule-picture.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
bash scripts/setup.sh
cmake --build "$build" --target lantern
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
"$build/game/lantern" --headless --frames 1 --screenshots 0 --out "$scratch/demo" --schedule "$scratch/schedule.dot"
dot -Tsvg "$scratch/schedule.dot" -o "$scratch/schedule.svg"
mkdir -p docs/frame
mv "$scratch/schedule.dot" docs/frame/schedule.dot
mv "$scratch/schedule.svg" docs/frame/schedule.svg
echo "updated docs/frame/schedule.dot and docs/frame/schedule.svg"
