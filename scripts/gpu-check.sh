#!/usr/bin/env bash
# Runs a scripts/gpu-check-pack.sh package on a machine with a GPU: the device, the GPU test
# binaries in shards (each test binary's shards at once, every process killed after
# TEST_LIMIT seconds), the headless demo at the game's defaults and at seed 000's look, and
# seed-table without the C++ reference. Logs go to LOGS; LOGS.tar.gz is rewritten after each
# phase, so a run stopped from outside still returns what it had.
#
#   scripts/gpu-check.sh [PACKAGE] [LOGS]        (defaults: .gpu-check, /tmp/gpu-check)
#   environment: SHARDS (8), TEST_LIMIT (120 s), ICD (the driver's Vulkan manifest; default
#   the NVIDIA container's), BINARIES (the test binaries to run; default all), DEMO_FRAMES
#   (600), SEED_TABLE_ROWS (e.g. 0,1; default every row)
#
# Run as root on a throwaway machine: it unpacks the .deb files into /.
set -uo pipefail
cd "$(dirname "$0")/.."
root=$PWD
pkg=$(realpath "${1:-.gpu-check}")
logs=${2:-/tmp/gpu-check}
shards=${SHARDS:-8}
limit=${TEST_LIMIT:-120}
frames=${DEMO_FRAMES:-600}
mkdir -p "$logs"
start=$(date +%s)
say() { echo "[$(($(date +%s) - start)) s] $*" | tee -a "$logs/summary.txt"; }
pack() { tar czf "$logs.tar.gz" -C "$(dirname "$logs")" "$(basename "$logs")"; }

for f in "$pkg"/deb/*.deb; do dpkg -x "$f" /; done
ldconfig
icd=${ICD:-/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json}
[ -f "$icd" ] || icd=$(find / -xdev -name '*_icd*.json' 2>/dev/null | head -1)
export VK_DRIVER_FILES=$icd VK_ICD_FILENAMES=$icd
export LD_LIBRARY_PATH=$pkg/lib:/usr/local/nvidia/lib64:/usr/local/nvidia/lib
# The tests look for their data under the source and build folders compiled into them.
src=$(cat "$pkg/source-dir")
if [ -n "$src" ] && [ ! -e "$src" ]; then
    mkdir -p "$(dirname "$src")"
    ln -sfn "$root" "$src"
fi
bdir=$(cat "$pkg/build-dir")
if [ ! -e "$bdir" ]; then
    mkdir -p "$(dirname "$bdir")"
    ln -sfn "$pkg/build" "$bdir"
fi
say "ICD $icd; source folder $src"
{ nvidia-smi -L; head -1 /etc/os-release; nproc; } 2>&1 | tee -a "$logs/summary.txt"

run_sharded() { # binary
    local t=$1 pids=()
    for i in $(seq 0 $((shards - 1))); do
        (GTEST_TOTAL_SHARDS=$shards GTEST_SHARD_INDEX=$i timeout -s KILL "$limit" "$pkg/bin/$t" \
             > "$logs/${t}_$i.txt" 2>&1
         echo "exit $?" >> "$logs/${t}_$i.txt") &
        pids+=($!)
    done
    wait "${pids[@]}" # not a bare wait: it would also wait for a process substitution
    local failed
    failed=$(cat "$logs/${t}"_*.txt | grep -c '^\[  FAILED  \].*ms)')
    say "$t: $(cat "$logs/${t}"_*.txt | grep -c '^\[       OK \]') passed, $failed failed," \
        "exits: $(grep -h '^exit ' "$logs/${t}"_*.txt | sort | uniq -c | tr -s ' \n' ' ')"
    grep -h '^\[  FAILED  \].*ms)' "$logs/${t}"_*.txt | tee -a "$logs/summary.txt"
    # a shard killed at the limit: the test it was in
    for f in "$logs/${t}"_*.txt; do
        grep -q '^exit 137' "$f" && say "  killed in: $(grep '^\[ RUN' "$f" | tail -1)"
    done
    pack
}

binaries=${BINARIES:-lantern_gpu_tests lantern_gi_gpu_tests lantern_texel_gpu_tests lantern_render_tests
    lantern_game_render_tests lantern_systems_tests lantern_bake_tests}
for t in $binaries; do
    run_sharded "$t"
done

demo() { # name, extra options...
    local name=$1
    shift
    (cd "$logs" && timeout -s KILL 120 "$pkg/bin/lantern" --headless --frames "$frames" --bench \
        --screenshots 1 --out "$logs/demo_$name" "$@" > "$logs/demo_$name.txt" 2>&1)
    say "demo $name: exit $?"
    { grep -E '^lantern headless demo:|^world:|^frame ms|^frames above|^memory from' "$logs/demo_$name.txt"
      grep -E '^[a-z_. ]+ +gpu ' "$logs/demo_$name.txt" | head -16; } | tee -a "$logs/summary.txt"
    pack
}
demo defaults
demo seed_look --set gi.resolution=8 --set gi.heat_scale=quarter --set gi.heat_rounds=20 --set gi.max_lights=64

rows=()
[ -n "${SEED_TABLE_ROWS:-}" ] && rows=(--row "$SEED_TABLE_ROWS")
timeout -s KILL 180 "$pkg/bin/lantern-bench" seed-table --no-reference "${rows[@]}" \
    --markdown "$logs/seed_table.md" > "$logs/seed_table.txt" 2>&1
say "seed-table: exit $?"
cat "$logs/seed_table.md" >> "$logs/summary.txt" 2>/dev/null
say "done"
pack
