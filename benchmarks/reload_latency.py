#!/usr/bin/env python3
"""Hot-reload latency (issue 20; docs/scenes.md, "Hot reload"): how long an edit of a watched
scene, or of the map it reads, takes to show up.

    python3 benchmarks/reload_latency.py [BUILD_DIR] [--edits N]

For each case it starts the real program with --watch, makes N edits (atomic replaces, as an
editor saves), and after each waits for the program's own counter to move (the game's
--status-file `reloads`; lantern-render's "watch: K rendered" line on stdout), never for a
fixed time. It prints, per case, the p50 and max of the wall time from the write to the
counter (what a designer waits for: the poll interval, the load, the world rebuilt, a frame)
and, for the game, the part it reports itself ("X ms from the change noticed to the new
world"), then the machine it ran on. Numbers depend on the machine's load: compare the rows
of one run.
"""
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def atomic_write(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def machine():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} threads, {platform.system()} {platform.release()}"


def percentile(values, q):
    s = sorted(values)
    return s[min(len(s) - 1, max(0, int(round(q * (len(s) - 1)))))]


def map_text(size, wall_column):
    rows = ["@" * size]
    for y in range(1, size - 1):
        row = ["."] * size
        row[0] = row[-1] = "@"
        if y % 4 == 1:
            row[wall_column] = "@"
        rows.append("".join(row))
    rows.append("@" * size)
    return f"type octile\nheight {size}\nwidth {size}\nmap\n" + "\n".join(rows) + "\n"


def scene_text(light_x, uses_map):
    world = '{"map": "level.map"}' if uses_map else '{"rows": ["################", "#..............#", ' \
        '"#..............#", "#......##......#", "#..............#", "#..............#", "################"]}'
    return (
        '{"lantern_scene": 1, "world": %s, "view": {"center": [8, 4], "size": [16, 9]},\n'
        ' "gi": {"resolution": 4, "heat_scale": "half", "heat_rounds": 16},\n'
        ' "point_lights": [{"position": [%.2f, 3.5], "color": [1.0, 0.85, 0.6], "intensity": 3.0, "radius": 10}]}\n'
        % (world, light_x)
    )


def wait_for(predicate, proc, what, deadline_s=300):
    end = time.monotonic() + deadline_s
    while time.monotonic() < end:
        value = predicate()
        if value is not None:
            return value
        if proc.poll() is not None:
            break
        time.sleep(0.002)
    raise SystemExit(f"reload_latency: {what}: never happened (exit status {proc.poll()})")


def watch_case(build, folder, edits, args, edit, own_pattern):
    """Starts the game headless with `args` and --watch, makes `edits` edits (edit(k) writes
    edit k), waits for each on the status file's reload counter; the wall times, and the
    game's own figures (own_pattern in its log)."""
    status = os.path.join(folder, "status.json")
    log_path = os.path.join(folder, "game.log")
    log = open(log_path, "w")
    proc = subprocess.Popen([os.path.join(build, "game", "lantern"), "--headless", *args, "--watch",
                             "--frames", "10000000", "--screenshots", "0", "--no-bake", "--status-file", status,
                             "--out", os.path.join(folder, "out")], stdout=log, stderr=subprocess.STDOUT)

    def reloads():
        try:
            with open(status) as f:
                m = re.search(r'"reloads": (\d+)', f.read())
                return int(m.group(1)) if m else None
        except OSError:
            return None

    try:
        wait_for(lambda: reloads(), proc, "the game's first frame")
        walls = []
        for k in range(1, edits + 1):
            start = time.monotonic()
            edit(k)
            wait_for(lambda: True if (reloads() or 0) >= k else None, proc, f"reload {k}")
            walls.append((time.monotonic() - start) * 1e3)
    finally:
        proc.terminate()
        proc.wait()
        log.close()
    with open(log_path) as f:
        own = [float(x) for x in re.findall(own_pattern, f.read())]
    return walls, own


def game_case(build, folder, edits, edit_map, map_size):
    scene = os.path.join(folder, "level.json")
    uses_map = edit_map or map_size > 0
    if uses_map:
        atomic_write(os.path.join(folder, "level.map"), map_text(max(map_size, 16), 7))
    atomic_write(scene, scene_text(4.5, uses_map))

    def edit(k):
        if edit_map:
            atomic_write(os.path.join(folder, "level.map"), map_text(max(map_size, 16), 7 + k % 3))
        else:
            atomic_write(scene, scene_text(4.5 + 0.25 * (k % 8), uses_map))

    return watch_case(build, folder, edits, ["--scene", scene], edit, r"scene reloaded \(\d+\): ([0-9.]+) ms")


def tables_case(build, folder, edits):
    """The caves (no scene) with --tables: each edit retints the torches, applied in place."""
    tables = os.path.join(folder, "tables.json")

    def tables_text(k):
        return ('{"lantern_tables": 1, "lights": {"torch": {"color": [1, %.3f, 0.3], "radius": %.2f}}}\n'
                % (0.5 + 0.05 * (k % 8), 6.0 + 0.25 * (k % 5)))

    atomic_write(tables, tables_text(0))
    return watch_case(build, folder, edits, ["--tables", tables], lambda k: atomic_write(tables, tables_text(k)),
                      r"tables reloaded \(\d+\): ([0-9.]+) ms")


def render_case(build, folder, edits):
    scene = os.path.join(folder, "level.json")
    atomic_write(scene, scene_text(4.5, False))
    out = open(os.path.join(folder, "render.out"), "w+")
    proc = subprocess.Popen([os.path.join(build, "tools", "render", "lantern-render"), scene, "--watch", "--quiet",
                             "--out", os.path.join(folder, "lit.png")], stdout=out, stderr=subprocess.STDOUT)

    def rendered():
        out.flush()
        with open(out.name) as f:
            counts = re.findall(r"watch: (\d+) rendered", f.read())
            return int(counts[-1]) if counts else None

    try:
        wait_for(rendered, proc, "lantern-render's first render")
        walls = []
        for k in range(1, edits + 1):
            start = time.monotonic()
            atomic_write(scene, scene_text(4.5 + 0.25 * (k % 8), False))
            wait_for(lambda: True if (rendered() or 0) >= k + 1 else None, proc, f"render {k + 1}")
            walls.append((time.monotonic() - start) * 1e3)
    finally:
        proc.terminate()
        proc.wait()
    with open(out.name) as f:
        own = [float(x) for x in re.findall(r"\(rendered, ([0-9.]+) ms\)", f.read())][1:]
    out.close()
    return walls, own


def main():
    args = sys.argv[1:]
    edits = 10
    if "--edits" in args:
        i = args.index("--edits")
        edits = int(args[i + 1])
        del args[i:i + 2]
    build = os.path.abspath(args[0] if args else os.path.join(ROOT, "build"))
    print(f"hot-reload latency, {edits} edits per case (ms; write to counter, and the program's own figure)")
    print(f"{'case':<46} {'p50':>8} {'max':>8} {'own p50':>9}")
    cases = [
        ("lantern --headless --watch: scene edit", lambda d: game_case(build, d, edits, False, 0)),
        ("lantern --headless --watch: map edit (16^2)", lambda d: game_case(build, d, edits, True, 16)),
        ("lantern --headless --watch: map edit (1024^2)", lambda d: game_case(build, d, edits, True, 1024)),
        ("lantern --headless --watch: tables edit (caves)", lambda d: tables_case(build, d, edits)),
        ("lantern-render --watch (lavapipe): scene edit", lambda d: render_case(build, d, edits)),
    ]
    for name, run in cases:
        with tempfile.TemporaryDirectory(prefix="lantern-reload-") as folder:
            walls, own = run(folder)
        own_p50 = f"{percentile(own, 0.5):9.1f}" if own else f"{'-':>9}"
        print(f"{name:<46} {percentile(walls, 0.5):8.1f} {max(walls):8.1f} {own_p50}", flush=True)
    print(f"machine: {machine()}")


if __name__ == "__main__":
    main()
