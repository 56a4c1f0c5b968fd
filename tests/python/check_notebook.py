"""The example notebook, executed headless (jupyter nbconvert --execute):
every cell ran, and its outputs hold an inline PNG and a film."""

import json
import sys

notebook = json.load(open(sys.argv[1], encoding="utf-8"))
outputs = [o for cell in notebook["cells"] if cell["cell_type"] == "code" for o in cell.get("outputs", [])]
errors = [o for o in outputs if o.get("output_type") == "error"]
assert not errors, f"a cell failed: {errors[0].get('ename')}: {errors[0].get('evalue')}"
assert all(cell.get("execution_count") for cell in notebook["cells"] if cell["cell_type"] == "code"), "a cell did not run"
pngs = [o for o in outputs if "image/png" in o.get("data", {})]
videos = [o for o in outputs if "<video" in "".join(o.get("data", {}).get("text/html", ""))]
assert pngs, "no inline PNG"
assert videos, "no film"
print(f"{len(pngs)} PNG and {len(videos)} film outputs")
