#!/usr/bin/python3
"""figgen against Ready on every 2-D formula pattern of Ready's repository:
docs/ready-patterns.md's table.

    RDY_BUILD=build-rdy /usr/bin/python3 scripts/ready/compare.py READY/Patterns WORK > docs/ready-patterns.md

(build/figgen must not be rebuilt while it runs.)

For each pattern: `figgen render P.vti --set steps=100 --format png,vti`
(does it run?); Ready's start (rdy_start) and Ready's 100 steps from it
(rdy), scripts/ready/run_pattern.sh; figgen's 100 steps from the same
start; the largest difference. Where that exceeds 1e-4, figgen runs the
pattern in double too: a pattern whose float and double runs differ as much
amplifies rounding, and no two float implementations agree on it.
Reads VTI files with Debian's VTK (python3-vtk9).
"""
import glob, os, re, subprocess, sys
import numpy as np
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
FIGGEN = os.path.join(HERE, '..', '..', 'build', 'figgen')


def arrays(path):
    r = vtk.vtkXMLImageDataReader(); r.SetFileName(path); r.Update()
    d = r.GetOutput().GetPointData()
    return {d.GetArrayName(i): vtk_to_numpy(d.GetArray(i)).astype(np.float64) for i in range(d.GetNumberOfArrays())}


def figgen(*args):
    return subprocess.run([FIGGEN, 'render', *args], capture_output=True, text=True)


def is_2d_formula(path):
    t = open(path, encoding='utf-8', errors='replace').read()
    rule = re.search(r'<rule[^>]*\stype="(\w+)"', t)
    extent = re.search(r'WholeExtent="([^"]*)"', t)
    if not rule or rule.group(1) != 'formula' or '<ImageData' not in t or not extent:
        return False
    e = list(map(int, extent.group(1).split()))
    return e[5] == e[4] and e[3] > e[2]


def main():
    patterns, work = sys.argv[1], sys.argv[2]
    rows = []
    for path in sorted(glob.glob(patterns + '/**/*.vti', recursive=True)):
        if not is_2d_formula(path):
            continue
        rel = os.path.relpath(path, patterns)[:-4]
        out = os.path.join(work, rel)
        os.makedirs(out, exist_ok=True)
        ran = figgen(path, '--set', 'steps=100', '--format', 'png,vti', '--out', out, '--set', 'id=own')
        row = {'pattern': rel, 'runs': ran.returncode == 0,
               'error': ran.stderr.strip().splitlines()[-1] if ran.returncode else ''}
        # Ready's runs are kept: a second pass (or one resumed) reuses them.
        if os.path.exists(out + '/ready100.vti') and os.path.exists(out + '/start.vti'):
            ready_ok = True
        else:
            ready_ok = subprocess.run(['bash', os.path.join(HERE, 'run_pattern.sh'), path, out],
                                      capture_output=True, text=True).returncode == 0
        if ready_ok and row['runs']:
            figgen(out + '/start.vti', '--set', 'steps=100', '--format', 'vti', '--out', out, '--set', 'id=float')
            a, b = arrays(out + '/float.vti'), arrays(out + '/ready100.vti')
            row['diff'] = max(float(np.max(np.abs(a[k] - b[k]))) for k in b)
            row['size'] = max(float(np.max(np.abs(b[k]))) for k in b)
            row['chemicals'] = len(b)
            if row['diff'] > 1e-4:
                figgen(out + '/start.vti', '--set', 'steps=100', '--set', 'data_type=double', '--format', 'vti',
                       '--out', out, '--set', 'id=double')
                c = arrays(out + '/double.vti')
                row['spread'] = max(float(np.max(np.abs(a[k] - c[k]))) for k in b)
        rows.append(row)
    agree = [r for r in rows if 'diff' in r and r['diff'] <= 1e-4]
    print('# Ready\'s 2-D formula patterns in figgen\n')
    print('Made by `scripts/ready/compare.py` (its docstring gives the command) from GollyGang/Ready\'s')
    print('Patterns/ folder: every 2-D pattern whose rule is a formula. "Runs": `figgen render P.vti')
    print('--set steps=100 --format png,vti` succeeds. Against Ready: from the same start (Ready\'s own,')
    print('saved by rdy_start), the largest difference of any chemical in any cell after 100 steps of')
    print('figgen and of Ready\'s `rdy` (PoCL 3.1 on the CPU), with the largest value for scale. Where it')
    print('exceeds 1e-4, "float vs double" is how far figgen\'s own float and double runs are apart: of')
    print('the same order (within a factor of 3), so the pattern amplifies rounding (chaotic maps such as `fmod(c + laplacian_c, 1)`,')
    print('divisions by near-zero gradients, values scaled by 1e6) and no two float implementations agree on it.\n')
    print(f'{sum(r["runs"] for r in rows)} of {len(rows)} run; {len(agree)} agree with Ready within 1e-4 '
          f'(the largest difference among them {max(r["diff"] for r in agree):.2g}); the other '
          f'{sum(1 for r in rows if "spread" in r)} amplify rounding.\n')
    print('| pattern | runs | chemicals | largest \\|value\\| | largest difference from Ready | float vs double |')
    print('|---|---|---|---|---|---|')
    for r in rows:
        if 'diff' not in r:
            print(f'| {r["pattern"]} | {"yes" if r["runs"] else "no: " + r["error"]} | | | | |')
            continue
        spread = f'{r["spread"]:.2g}' if 'spread' in r else ''
        print(f'| {r["pattern"]} | yes | {r["chemicals"]} | {r["size"]:.3g} | {r["diff"]:.2g} | {spread} |')


main()
