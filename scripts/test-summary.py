#!/usr/bin/env python3
"""One summary line of a CTest run from its JUnit file (ctest --output-junit).

    test-summary.py NAME JUNIT.xml

prints, for example,
    full suite: 612 tests, 604 passed, 0 failed, 8 skipped (8: ../shared is absent)
grouping the skipped tests by the reason GTEST_SKIP gave (the line after "Skipped" in the
test's output), so a skip is never silent. Exit status 0; 2 when the file cannot be read.
"""
import re
import sys
import xml.etree.ElementTree as ET
from collections import Counter


def skip_reason(output: str) -> str:
    m = re.search(r": Skipped\n(.*)", output)
    if not m or not m.group(1).strip() or m.group(1).startswith("[  SKIPPED ]"):
        return "no reason given"
    reason = m.group(1).strip()
    return reason if len(reason) <= 100 else reason[:97] + "..."


def main() -> int:
    if len(sys.argv) != 3:
        print("usage: test-summary.py NAME JUNIT.xml", file=sys.stderr)
        return 2
    name, path = sys.argv[1], sys.argv[2]
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        print(f"test-summary: {path}: {e}", file=sys.stderr)
        return 2
    passed = failed = 0
    reasons: Counter = Counter()
    for case in root.iter("testcase"):
        if case.find("skipped") is not None:
            out = case.find("system-out")
            reasons[skip_reason(out.text or "" if out is not None else "")] += 1
        elif case.find("failure") is not None or case.find("error") is not None or case.get("status") == "fail":
            failed += 1
        else:
            passed += 1
    skipped = sum(reasons.values())
    line = f"{name}: {passed + failed + skipped} tests, {passed} passed, {failed} failed, {skipped} skipped"
    if skipped:
        line += " (" + "; ".join(f"{n}: {r}" for r, n in reasons.most_common()) + ")"
    print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
