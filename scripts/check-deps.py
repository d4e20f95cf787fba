#!/usr/bin/env python3
"""Proves that scripts/setup.sh installs everything the build and the tests use.

Every system file the build and the test suite touch must belong to a Debian package that
setup.sh names, or that one of those pulls in through Depends/Pre-Depends (recursively), or
that is part of every Debian system (Essential: yes, or Priority: required). A file that belongs to no such package fails the
check with the package's name: it is on this machine only because someone (or earlier work)
installed it, and a fresh machine would not have it.

What is checked:
  headers     every system header the compiler read (ninja's dependency log, `ninja -t deps`,
              of each build folder given);
  libraries   every shared library the built executables load (`ldd`);
  executables the programs the build, the scripts and the tests run: the FILEPATH programs in
              CMakeCache.txt (compiler, glslangValidator, ...), the programs the tests spawn
              (found in tests/ by their `run_tool({"name"` and `posix_spawnp(..., "name"` calls)
              and the fixed list SCRIPT_TOOLS below.

The dependency closure comes from dpkg's own database (/var/lib/dpkg/status): the packages
installed here, their Depends/Pre-Depends and Provides. It is exact for this machine without
network or apt lists, where `apt-cache depends` needs `apt-get update` first.

Usage:
  check-deps.py [--packages-from FILE] [--source DIR] BUILD_DIR [BUILD_DIR ...]
Exit status: 0 when everything is covered, 1 when something is not (each file is listed with
its package), 2 on a usage error (a missing build folder, no PACKAGES list, no dpkg).
"""
from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

# Programs the project's shell scripts run (scripts/*.sh, .ci/run), beyond those CMake found.
SCRIPT_TOOLS = ["bash", "cmake", "ctest", "ninja", "python3", "git", "apt-get", "dpkg-query",
                "Xvfb", "xdotool", "xwd", "glslangValidator", "timeout", "nproc", "awk", "sed",
                "clang", "clang++", "dot"]

SYSTEM_PATH = "/usr/sbin:/usr/bin:/sbin:/bin"
DPKG_STATUS = Path(os.environ.get("LANTERN_DPKG_STATUS", "/var/lib/dpkg/status"))


def fail_usage(message: str) -> None:
    print(f"check-deps: {message}", file=sys.stderr)
    sys.exit(2)


def named_packages(setup: Path) -> list[str]:
    """The PACKAGES=( ... ) array of setup.sh (comments and line breaks allowed)."""
    try:
        text = setup.read_text()
    except OSError as e:
        fail_usage(f"{setup}: {e.strerror}")
    m = re.search(r"^PACKAGES=\((.*?)^\)", text, re.S | re.M)
    if not m:
        fail_usage(f"{setup}: no PACKAGES=( ... ) list")
    words = []
    for line in m.group(1).splitlines():
        words += line.split("#", 1)[0].split()
    return words


def read_dpkg_status() -> dict[str, dict[str, str]]:
    """Installed packages: name -> fields (Depends, Pre-Depends, Provides, Essential)."""
    if not DPKG_STATUS.is_file():
        fail_usage(f"{DPKG_STATUS} not found: this check needs a Debian system")
    packages: dict[str, dict[str, str]] = {}
    for stanza in DPKG_STATUS.read_text(errors="replace").split("\n\n"):
        fields: dict[str, str] = {}
        key = None
        for line in stanza.splitlines():
            if line.startswith((" ", "\t")) and key:
                fields[key] += " " + line.strip()
            elif ":" in line:
                key, _, value = line.partition(":")
                fields[key] = value.strip()
        name = fields.get("Package")
        if name and "install ok installed" in fields.get("Status", ""):
            packages[name] = fields
    return packages


def dependency_names(field: str) -> list[list[str]]:
    """'a (>= 1) | b:any, c' -> [['a', 'b'], ['c']]"""
    groups = []
    for group in field.split(","):
        alternatives = []
        for alt in group.split("|"):
            alt = alt.strip()
            if not alt:
                continue
            alternatives.append(re.split(r"[\s(\[]", alt, 1)[0].split(":", 1)[0])
        if alternatives:
            groups.append(alternatives)
    return groups


def closure(roots: list[str], installed: dict[str, dict[str, str]]) -> set[str]:
    """The installed packages reached from roots through Depends and Pre-Depends."""
    providers: dict[str, list[str]] = {}
    for name, fields in installed.items():
        for group in dependency_names(fields.get("Provides", "")):
            for virtual in group:
                providers.setdefault(virtual, []).append(name)
    reached: set[str] = set()
    stack = list(roots)
    while stack:
        name = stack.pop()
        candidates = [name] if name in installed else providers.get(name, [])
        for pkg in candidates:
            if pkg in reached:
                continue
            reached.add(pkg)
            fields = installed[pkg]
            for field in ("Depends", "Pre-Depends"):
                for alternatives in dependency_names(fields.get(field, "")):
                    stack.extend(a for a in alternatives if a in installed or a in providers)
    return reached


def header_files(build: Path, source: Path) -> dict[str, str]:
    """System files in ninja's dependency log: path -> one object that read it."""
    out = subprocess.run(["ninja", "-C", str(build), "-t", "deps"], capture_output=True, text=True)
    if out.returncode != 0:
        fail_usage(f"ninja -t deps in {build} failed: {out.stderr.strip()}")
    files: dict[str, str] = {}
    target = ""
    roots = (str(source.resolve()) + os.sep, str(build.resolve()) + os.sep)
    for line in out.stdout.splitlines():
        if not line.startswith(" "):
            target = line.split(":", 1)[0]
            continue
        path = line.strip()
        if not path.startswith("/"):
            continue  # relative: inside the build folder
        path = os.path.normpath(path)
        if path.startswith(roots) or path.startswith("/tmp/"):
            continue
        files.setdefault(path, target)
    return files


def elf_files(build: Path) -> list[Path]:
    found = []
    for root, dirs, names in os.walk(build):
        dirs[:] = [d for d in dirs if d not in ("CMakeFiles",)]
        for name in names:
            p = Path(root) / name
            if not os.access(p, os.X_OK) or not p.is_file() or p.suffix in (".sh", ".py", ".cmake"):
                continue
            with open(p, "rb") as f:
                if f.read(4) == b"\x7fELF":
                    found.append(p)
    return found


def shared_libraries(build: Path) -> dict[str, str]:
    libs: dict[str, str] = {}
    for exe in elf_files(build):
        out = subprocess.run(["ldd", str(exe)], capture_output=True, text=True)
        for line in out.stdout.splitlines():
            m = re.search(r"=>\s*(/\S+)", line) or re.match(r"\s*(/\S+)", line)
            if m:
                libs.setdefault(os.path.normpath(m.group(1)), str(exe.relative_to(build)))
            elif "not found" in line:
                libs.setdefault("missing:" + line.split()[0], str(exe.relative_to(build)))
    return libs


def test_tools(source: Path) -> dict[str, str]:
    tools: dict[str, str] = {}
    pattern = re.compile(r'(?:run_tool\(\{|posix_spawnp\([^,]+,\s*)"([A-Za-z0-9_.+-]+)"')
    for path in sorted((source / "tests").rglob("*.cpp")):
        for m in pattern.finditer(path.read_text(errors="replace")):
            tools.setdefault(m.group(1), str(path.relative_to(source)))
    return tools


def cmake_programs(build: Path) -> dict[str, str]:
    programs: dict[str, str] = {}
    cache = build / "CMakeCache.txt"
    if not cache.is_file():
        return programs
    for line in cache.read_text(errors="replace").splitlines():
        m = re.match(r"([A-Za-z0-9_]+):FILEPATH=(/\S+)$", line)
        if m and os.access(m.group(2), os.X_OK) and not m.group(2).startswith(str(build.resolve())):
            programs.setdefault(m.group(2), f"CMakeCache {m.group(1)}")
    return programs


def owners(paths: list[str]) -> dict[str, set[str]]:
    """path -> packages owning it (dpkg -S), trying the resolved path and /usr-merge twins."""
    def variants(p: str) -> list[str]:
        out = [p, os.path.realpath(p)]
        for v in list(out):
            if v.startswith("/usr/lib/") or v.startswith("/usr/bin/") or v.startswith("/usr/sbin/"):
                out.append(v[4:])
            elif v.startswith(("/lib/", "/lib64/", "/bin/", "/sbin/")):
                out.append("/usr" + v)
        return list(dict.fromkeys(out))

    query = sorted({v for p in paths for v in variants(p)})
    owned: dict[str, set[str]] = {}
    for i in range(0, len(query), 400):
        out = subprocess.run(["dpkg", "-S", *query[i:i + 400]], capture_output=True, text=True)
        for line in out.stdout.splitlines():
            if line.startswith("diversion "):
                continue
            pkgs, sep, path = line.partition(": ")
            if not sep:
                continue
            owned.setdefault(path.strip(), set()).update(
                p.strip().split(":", 1)[0] for p in pkgs.split(","))
    result = {}
    for p in paths:
        pkgs: set[str] = set()
        for v in variants(p):
            pkgs |= owned.get(v, set())
        result[p] = pkgs
    return result


def main() -> int:
    here = Path(__file__).resolve().parent.parent
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("builds", nargs="+", type=Path, metavar="BUILD_DIR")
    ap.add_argument("--packages-from", type=Path, default=here / "scripts" / "setup.sh",
                    help="the setup script whose PACKAGES list is checked (default scripts/setup.sh)")
    ap.add_argument("--source", type=Path, default=here, help="the source tree (default: this checkout)")
    args = ap.parse_args()
    if not shutil.which("dpkg"):
        fail_usage("dpkg not found: this check needs a Debian system")

    installed = read_dpkg_status()
    named = named_packages(args.packages_from)
    not_installed = [p for p in named if p not in installed]
    # The base system: Essential packages and those of Priority required, which every Debian
    # installation has (debootstrap's minbase, the debian:12 container image).
    essential = [n for n, f in installed.items()
                 if f.get("Essential", "").lower() == "yes" or f.get("Priority", "") == "required"]
    allowed = closure(named + essential, installed)

    used: dict[str, tuple[str, str]] = {}  # path -> (kind, who uses it)
    for build in args.builds:
        if not (build / "build.ninja").is_file():
            fail_usage(f"{build}: not a Ninja build folder (build it first: bash scripts/build.sh {build})")
        for p, who in header_files(build, args.source).items():
            used.setdefault(p, ("header", who))
        for p, who in shared_libraries(build).items():
            used.setdefault(p, ("library", who))
        for p, who in cmake_programs(build).items():
            used.setdefault(p, ("program", who))
    missing_tools = []
    for tool, who in {**{t: "scripts" for t in SCRIPT_TOOLS}, **test_tools(args.source)}.items():
        # Looked up where Debian's packages put programs, not on this session's PATH: a
        # program found only in /usr/local or a home folder was installed by hand.
        path = shutil.which(tool, path=SYSTEM_PATH)
        if path:
            used.setdefault(os.path.normpath(path), ("program", who))
        else:
            missing_tools.append(f"{tool} (run by {who})")

    problems: list[str] = []
    unowned_libs = [p for p in used if p.startswith("missing:")]
    for p in unowned_libs:
        problems.append(f"library {p[8:]} needed by {used[p][1]} is not installed")
        del used[p]
    by_package: dict[str, list[str]] = {}
    for path, pkgs in sorted(owners(sorted(used)).items()):
        kind, who = used[path]
        if not pkgs:
            problems.append(f"{kind} {path} (used by {who}) belongs to no Debian package: installed by hand?")
        elif not pkgs & allowed:
            by_package.setdefault(" or ".join(sorted(pkgs)), []).append(f"{kind} {path} (used by {who})")
    for pkg, files in sorted(by_package.items()):
        shown = files[:3] + ([f"... and {len(files) - 3} more"] if len(files) > 3 else [])
        problems.append(f"package {pkg} is used but {args.packages_from.name} neither names it nor pulls it in:\n    "
                        + "\n    ".join(shown))
    problems += [f"program {t} is not installed by any Debian package" for t in missing_tools]
    problems += [f"{args.packages_from.name} names {p}, which is not installed (run it)" for p in not_installed]

    files = len(used)
    if problems:
        print(f"check-deps: {len(problems)} problem(s) among {files} system files used:", file=sys.stderr)
        for p in problems:
            print(f"  {p}", file=sys.stderr)
        missing_names = sorted(by_package)
        if missing_names:
            print(f"check-deps: add to PACKAGES in {args.packages_from}: {' '.join(missing_names)}", file=sys.stderr)
        return 1
    print(f"check-deps: {files} system files used (headers, libraries, programs) all come from the "
          f"{len(named)} packages {args.packages_from.name} names or their {len(allowed) - len(named)} dependencies")
    return 0


if __name__ == "__main__":
    sys.exit(main())
