#!/usr/bin/env python3
"""The summary `make test` prints after ctest, from this run's own JUnit file (ctest --output-junit).

Prints the "[cases]", "[ulps]" and "[agreement]" lines every test wrote (sorted), the tests that
were skipped with the reason each gave, the failed ones, and last a line

    ctest: N passed, N failed, N skipped

Exit status: 1 when a test failed, when the file names no test, or when a test was skipped and
the environment does not allow skips (RAYCORE_ALLOW_SKIPS=1: for a user without the shared test
models; CI never sets it). A skipped check is not a passed one.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

SUMMARY = re.compile(r"^\[(cases|ulps|agreement)\]")
SKIP_REASON = re.compile(r"^.*: Skipped\n(.*)$", re.MULTILINE)


def main(argv):
    if len(argv) != 2:
        print("usage: ctest_summary.py JUNIT.xml", file=sys.stderr)
        return 2
    try:
        root = ET.parse(argv[1]).getroot()
    except (OSError, ET.ParseError) as e:
        print(f"ctest_summary: cannot read {argv[1]}: {e}", file=sys.stderr)
        return 1
    lines, skipped, failed, passed = [], [], [], 0
    for case in root.iter("testcase"):
        name = case.get("name", "?")
        out = case.findtext("system-out") or ""
        lines += [ln for ln in out.splitlines() if SUMMARY.match(ln)]
        if case.find("skipped") is not None or case.get("status") == "notrun":
            m = SKIP_REASON.search(out)
            skipped.append((name, m.group(1).strip() if m else "not run"))
        elif case.find("failure") is not None or case.find("error") is not None or \
                case.get("status") not in ("run", None):
            failed.append(name)
        else:
            passed += 1
    print("---- cases run (from this run's ctest JUnit output) ----")
    for ln in sorted(lines):
        print(ln)
    for name in failed:
        print(f"failed: {name}")
    for name, why in skipped:
        print(f"skipped: {name}: {why}")
    allow = os.environ.get("RAYCORE_ALLOW_SKIPS") == "1"
    if skipped and not allow:
        print(f"{len(skipped)} tests were skipped: a skipped check is not a pass. Put the shared "
              "test models at ../shared/models or name them with RAYCORE_MODELS_PATH (README, "
              "\"Test models\"), or set RAYCORE_ALLOW_SKIPS=1 to accept the skips")
    total = passed + len(failed) + len(skipped)
    print(f"ctest: {passed} passed, {len(failed)} failed, {len(skipped)} skipped")
    if total == 0:
        print("ctest_summary: no test ran", file=sys.stderr)
        return 1
    return 1 if failed or (skipped and not allow) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
