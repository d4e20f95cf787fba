#!/usr/bin/env python3
"""Writes the example maps in game/maps/ (see game/maps/README.md). Deterministic."""
import random
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "game" / "maps"


def write(name, grid):
    with open(OUT / name, "w") as f:
        f.write(f"type octile\nheight {len(grid)}\nwidth {len(grid[0])}\nmap\n")
        for row in grid:
            f.write("".join(row) + "\n")


def keep():
    w, h = 64, 48
    g = [["@" if x in (0, w - 1) or y in (0, h - 1) else "." for x in range(w)] for y in range(h)]

    def rect(x0, y0, x1, y1):
        for x in range(x0, x1 + 1):
            g[y0][x] = g[y1][x] = "@"
        for y in range(y0, y1 + 1):
            g[y][x0] = g[y][x1] = "@"

    rect(16, 10, 47, 37)  # the keep's outer wall
    for x in range(16, 48):
        g[22][x] = "@"
    for y in range(10, 38):
        g[y][31] = "@"
    for y in range(22, 38):
        g[y][39] = "@"
    for x, y in [(31, 16), (31, 30), (24, 22), (43, 22), (39, 28), (16, 30), (47, 16), (31, 37), (32, 37)]:
        g[y][x] = "."  # doors
    for x, y in [(20, 14), (26, 14), (20, 18), (26, 18)]:
        g[y][x] = "@"  # pillars of the great hall
    for y in range(38, 45):
        for x in range(4, 13):
            if (x - 8) ** 2 / 16 + (y - 41) ** 2 / 9 <= 1:
                g[y][x] = "W"  # the pond
    rnd = random.Random(7)
    for _ in range(70):
        x, y = rnd.randrange(2, w - 2), rnd.randrange(2, h - 2)
        if g[y][x] == "." and not (15 <= x <= 48 and 9 <= y <= 38):
            g[y][x] = "T"
    write("keep.map", g)


def caverns():
    w = h = 192
    rnd = random.Random(11)
    g = [["@" if rnd.random() < 0.46 else "." for _ in range(w)] for _ in range(h)]
    for _ in range(4):  # cellular-automaton smoothing: a wall where 5 of 9 are walls
        n = [[None] * w for _ in range(h)]
        for y in range(h):
            for x in range(w):
                walls = sum(1 for dy in (-1, 0, 1) for dx in (-1, 0, 1)
                            if not (0 <= x + dx < w and 0 <= y + dy < h) or g[y + dy][x + dx] == "@")
                n[y][x] = "@" if walls >= 5 else "."
        g = n
    for y in range(h):
        for x in range(w):
            if x in (0, w - 1) or y in (0, h - 1):
                g[y][x] = "@"
            elif g[y][x] == "." and rnd.random() < 0.012:
                g[y][x] = "T"
    write("caverns.map", g)


if __name__ == "__main__":
    keep()
    caverns()
