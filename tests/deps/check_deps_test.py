#!/usr/bin/env python3
"""The set-up check reports a package that setup.sh stops naming.

For each package below (one the build includes a header of, one whose program builds the
shaders, one the window tests run), a copy of scripts/setup.sh without it must make
scripts/check-deps.py fail and name that package; the unchanged list must pass. No other
listed package pulls these in, so the check has to notice.

usage: check_deps_test.py BUILD_DIR
"""
import re
import subprocess
import sys
import tempfile
from pathlib import Path

SOURCE = Path(__file__).resolve().parents[2]
CHECK = SOURCE / "scripts" / "check-deps.py"
SETUP = SOURCE / "scripts" / "setup.sh"
TAKEN_OFF = ["libxrandr-dev", "glslang-tools", "xdotool"]


def run(build: str, setup: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(CHECK), "--packages-from", str(setup), build],
                          capture_output=True, text=True)


def main() -> int:
    build = sys.argv[1]
    failures = []
    whole = run(build, SETUP)
    if whole.returncode != 0:
        failures.append(f"the full list fails the check:\n{whole.stderr}")
    text = SETUP.read_text()
    for pkg in TAKEN_OFF:
        pattern = re.compile(rf"(?<=[\s(]){re.escape(pkg)}(?=\s)")
        if not pattern.search(text):
            failures.append(f"{pkg} is not in {SETUP}: update this test")
            continue
        with tempfile.TemporaryDirectory() as tmp:
            copy = Path(tmp) / "setup.sh"
            copy.write_text(pattern.sub("", text, count=1))
            result = run(build, copy)
        if result.returncode != 1:
            failures.append(f"without {pkg}: exit {result.returncode}, expected 1\n{result.stdout}{result.stderr}")
        elif f"package {pkg} is used" not in result.stderr or f"add to PACKAGES in {copy}: " not in result.stderr:
            failures.append(f"without {pkg}: the report does not name it:\n{result.stderr}")
        else:
            print(f"without {pkg}: reported\n{result.stderr}")
    for f in failures:
        print(f"FAIL: {f}", file=sys.stderr)
    print(f"{len(TAKEN_OFF) + 1 - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
