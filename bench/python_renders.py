"""make bench: twenty renders of tc7-1, each with its own r, in one Python
process against twenty `figgen render` processes doing the same (issue 37's
target: the first at most half the second). Prints both, and the ratio, as
one line of JSON for bench/results/python.json."""

import json
import subprocess
import sys
import tempfile
import time

import figgen

figgen_exe = sys.argv[1]
rates = [round(0.01 * (i + 1), 2) for i in range(20)]  # 0.01 .. 0.20, all within the model's 0.25

with tempfile.TemporaryDirectory() as out:
    started = time.perf_counter()
    for r in rates:
        subprocess.run([figgen_exe, "render", "tc7-1", "--set", f"r={r}", "--format", "png", "--out", out], check=True)
    processes = time.perf_counter() - started

with tempfile.TemporaryDirectory() as out:
    started = time.perf_counter()
    for r in rates:
        figgen.render("tc7-1", set={"r": r}, formats=("png",), out=out)
    in_process = time.perf_counter() - started

result = {"renders": len(rates), "figure": "tc7-1", "processes_s": round(processes, 3),
          "in_process_s": round(in_process, 3), "ratio": round(in_process / processes, 3)}
print(json.dumps(result))
