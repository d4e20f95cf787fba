#!/usr/bin/env bash
# Regenerates the golden images tests/golden/<scene>.png from tests/golden/<scene>.json with
# the C++ reference backend (the specification). Review the new images before committing.
#   bash scripts/update-goldens.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
cmake --build "$build" --target lantern-render
for scene in tests/golden/*.json; do
    "$build/tools/render/lantern-render" "$scene" --backend cpu --quiet --out "${scene%.json}.png"
    echo "updated ${scene%.json}.png"
done
