#!/usr/bin/python3
"""Times every test alone and prints tests/test_costs.cmake: ctest's COST
for each test of a second or more, so that a fresh clone, which has no
timing data of ctest's own, starts the longest tests first.

    scripts/test-costs.py build > tests/test_costs.cmake

Runs the tests one after another (a few minutes); each as ctest would,
with its environment and working folder, from `ctest --show-only=json-v1`.
"""
import json, os, subprocess, sys, time

HEADER = """\
# Costs for ctest's order (tests/CMakeLists.txt includes this file after
# the tests are declared).
#
# ctest starts the longest tests first when it knows their times from an
# earlier run (Testing/Temporary/CTestCostData.txt). A fresh clone has
# none, and ctest would start the tests in the order they are declared:
# the golden, browser and Python tests, declared last, would run at the
# end, side by side (make test took 121 s in a fresh clone against 104 s
# with the times known). These are the tests of a second or more, with
# their seconds alone on a 2-core machine; a name that is no longer a test
# is ignored, and ctest's own data takes over after the first run.
# Made by: scripts/test-costs.py build > tests/test_costs.cmake
"""


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    listing = json.loads(subprocess.check_output(["ctest", "--test-dir", build, "--show-only=json-v1"]))
    rows = []
    for test in listing["tests"]:
        env, cwd = dict(os.environ), None
        for prop in test.get("properties", []):
            if prop["name"] == "ENVIRONMENT":
                for pair in prop["value"]:
                    key, value = pair.split("=", 1)
                    env[key] = value
            elif prop["name"] == "WORKING_DIRECTORY":
                cwd = prop["value"]
        start = time.monotonic()
        subprocess.run(test["command"], env=env, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rows.append((time.monotonic() - start, test["name"]))
        print(f"{rows[-1][0]:6.2f} {test['name']}", file=sys.stderr)
    rows.sort(key=lambda r: -r[0])
    print(HEADER, end="")
    for seconds, name in rows:
        if seconds < 1.0:
            break
        if any(c in name for c in '"\\$;'):
            print(f"# not listed (a character CMake would read): {name}")
            continue
        print(f'set_tests_properties("{name}" PROPERTIES COST {seconds:.1f})')


if __name__ == "__main__":
    main()
