#!/usr/bin/env bash
# Packs a build for a run on another Linux machine with a GPU and no build tools
# (docs/performance.md, "On an NVIDIA H100"): the GPU test binaries, the game and the
# benchmarks, stripped, with the shared libraries they load that a bare image may lack, and
# Debian's Vulkan loader and validation layer as .deb files. scripts/gpu-check.sh runs them.
#
#   scripts/gpu-check-pack.sh [BUILD_DIR] [DEST]      (defaults: build, .gpu-check)
#
# DEST lands inside the checkout and is ignored by git (.git/info/exclude), so a tool that
# copies the working tree can carry it. The tests find their data through the source folder
# compiled into them; gpu-check.sh links that path to the checkout it runs in.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "${1:-build}")
dest=${2:-.gpu-check}
[ -f "$build/CMakeCache.txt" ] || { echo "gpu-check-pack: $build is not a build folder" >&2; exit 2; }
rm -rf "$dest"
mkdir -p "$dest/bin" "$dest/lib" "$dest/deb"
bins=(game/lantern tools/bench/lantern-bench tests/gpu/lantern_gpu_tests tests/gi/lantern_gi_gpu_tests
      tests/texel/lantern_texel_gpu_tests tests/render/lantern_render_tests
      tests/game/lantern_game_render_tests tests/systems/lantern_systems_tests tests/bake/lantern_bake_tests)
for b in "${bins[@]}"; do
    [ -x "$build/$b" ] || { echo "gpu-check-pack: $build/$b is missing (build it first)" >&2; exit 2; }
    strip -o "$dest/bin/$(basename "$b")" "$build/$b"
done
mkdir -p "$dest/build/tests/gpu"
cp -r "$build/tests/gpu/lantern_test_shaders" "$dest/build/tests/gpu/"
# Everything the binaries load except the C runtime, which the target's own is newer than.
for b in "$dest"/bin/*; do ldd "$b"; done | awk '/=> \// {print $3}' | sort -u |
    grep -v -E '/(libc|libm|libdl|libpthread|librt|libstdc\+\+|libgcc_s)\.so' |
    while read -r lib; do cp -L "$lib" "$dest/lib/"; done
(cd "$dest/deb" && apt-get download libvulkan1 vulkan-validationlayers >/dev/null)
echo "$build" > "$dest/build-dir" # LANTERN_BINARY_DIR, compiled into the tests
grep -m1 '^CMAKE_HOME_DIRECTORY' "$build/CMakeCache.txt" | cut -d= -f2 > "$dest/source-dir" # LANTERN_SOURCE_DIR
grep -qx "/$dest/" .git/info/exclude 2>/dev/null || { mkdir -p .git/info; echo "/$dest/" >> .git/info/exclude; }
du -sh "$dest"
