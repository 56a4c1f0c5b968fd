#!/usr/bin/python3
"""figgen against Ready on every pattern file of Ready's repository:
docs/ready-patterns.md's table.

    RDY_BUILD=build-rdy /usr/bin/python3 scripts/ready/compare.py READY/Patterns WORK > docs/ready-patterns.md

(build/figgen must not be rebuilt while it runs; FIGGEN=path runs another copy.)

Every .vti and .vtu under Patterns/ is listed with its kind: its rule
(formula, inbuilt, kernel) and its grid (1-D, 2-D, 3-D image, or a mesh).
For each that figgen runs (formula and inbuilt rules on images): `figgen
render P.vti --set steps=100 --format png,vti` (does it run?); Ready's start
(rdy_start) and Ready's 100 steps from it (rdy),
scripts/ready/run_pattern.sh; figgen's 100 steps from the same start; the
largest difference. Where that exceeds 1e-4, figgen runs the pattern in
double too: a pattern whose float and double runs differ as much
amplifies rounding, and no two float implementations agree on it.
Reads VTI files with Debian's VTK (python3-vtk9).
"""
import glob, os, re, subprocess, sys
import numpy as np
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
FIGGEN = os.environ.get('FIGGEN', os.path.join(HERE, '..', '..', 'build', 'figgen'))


def arrays(path):
    r = vtk.vtkXMLImageDataReader(); r.SetFileName(path); r.Update()
    d = r.GetOutput().GetPointData()
    return {d.GetArrayName(i): vtk_to_numpy(d.GetArray(i)).astype(np.float64) for i in range(d.GetNumberOfArrays())}


def figgen(*args):
    return subprocess.run([FIGGEN, 'render', *args], capture_output=True, text=True)


def kind_of(path):
    """(rule type, grid): ('formula', '2-D'), ('kernel', 'mesh'), ..."""
    t = open(path, encoding='utf-8', errors='replace').read()
    rule = re.search(r'<rule[^>]*\stype="(\w+)"', t)
    rule = rule.group(1) if rule else '?'
    if '<UnstructuredGrid' in t or path.endswith('.vtu'):
        return rule, 'mesh'
    extent = re.search(r'WholeExtent="([^"]*)"', t)
    if not extent:
        return rule, '?'
    e = list(map(int, extent.group(1).split()))
    sides = [e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1]
    return rule, '%d-D' % max(1, sum(1 for n in sides if n > 1))


def runnable(kind):
    return kind[0] in ('formula', 'inbuilt') and kind[1] != 'mesh'


def main():
    patterns, work = sys.argv[1], sys.argv[2]
    rows = []
    files = sorted(glob.glob(patterns + '/**/*.vti', recursive=True) + glob.glob(patterns + '/**/*.vtu', recursive=True))
    for path in files:
        kind = kind_of(path)
        rel = os.path.relpath(path, patterns)[:-4]
        if not runnable(kind):
            rows.append({'pattern': rel, 'kind': kind, 'runs': False, 'error': 'not yet (issue 50)'})
            continue
        out = os.path.join(work, rel)
        os.makedirs(out, exist_ok=True)
        ran = figgen(path, '--set', 'steps=100', '--format', 'png,vti', '--out', out, '--set', 'id=own')
        row = {'pattern': rel, 'kind': kind, 'runs': ran.returncode == 0,
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
            row['bits'] = all(np.array_equal(a[k], b[k]) for k in b)
            row['size'] = max(float(np.max(np.abs(b[k]))) for k in b)
            row['chemicals'] = len(b)
            if row['diff'] > 1e-4 * max(1.0, row['size']):
                figgen(out + '/start.vti', '--set', 'steps=100', '--set', 'data_type=double', '--format', 'vti',
                       '--out', out, '--set', 'id=double')
                c = arrays(out + '/double.vti')
                row['spread'] = max(float(np.max(np.abs(a[k] - c[k]))) for k in b)
        rows.append(row)
    ran = [r for r in rows if runnable(r['kind'])]
    agree = [r for r in ran if 'diff' in r and r['diff'] <= 1e-4 * max(1.0, r['size'])]
    bits = [r for r in ran if r.get('bits')]
    print('# Ready\'s patterns in figgen\n')
    print('Made by `scripts/ready/compare.py` (its docstring gives the command) from GollyGang/Ready\'s')
    print('Patterns/ folder: every pattern file, with its kind (the rule: formula, inbuilt or kernel; the')
    print('grid: 1-D, 2-D or 3-D image, or mesh). "Runs": `figgen render P.vti --set steps=100 --format')
    print('png,vti` succeeds. Against Ready: from the same start (Ready\'s own, saved by rdy_start), the')
    print('largest difference of any chemical in any cell after 100 steps of figgen and of Ready\'s `rdy`')
    print('(PoCL 3.1 on the CPU for formulas, its own C++ for the inbuilt Gray-Scott), with the largest')
    print('value for scale; "bits" where every value is the same float. figgen runs Ready\'s formulas')
    print('in Ready\'s OpenCL arithmetic (`arithmetic = "opencl"`: a * b + c inside one expression is one')
    print('fused multiply-add, as pocl\'s clang contracts it); what still differs by a unit in the last')
    print('place comes mostly from OpenCL\'s built-in functions (pocl\'s pow, exp, sin, atan2 round')
    print('differently from glibc\'s). Where the difference exceeds 1e-4 x max(1, largest |value|),')
    print('"float vs double" is how far figgen\'s own float and')
    print('double runs are apart: of the same order (within a factor of 3), so the pattern amplifies rounding')
    print('(chaotic maps such as `fmod(c + laplacian_c, 1)`, divisions by near-zero gradients, values')
    print('scaled by 1e6) and no two float implementations agree on it. Kernel rules and meshes are issue 50.\n')
    kinds = {}
    for r in rows:
        kinds.setdefault('%s, %s' % r['kind'], []).append(r)
    print(f'{len(rows)} pattern files. Of the {len(ran)} figgen runs (formula and inbuilt rules on images), '
          f'{sum(r["runs"] for r in ran)} run; {len(bits)} are Ready\'s numbers to the bit and {len(agree)} agree '
          f'within 1e-4 x max(1, largest |value|); {sum(1 for r in ran if "spread" in r)} amplify rounding.\n')
    print('| kind | files | run | to the bit | within 1e-4 of Ready |')
    print('|---|---|---|---|---|')
    for k in sorted(kinds):
        rs = kinds[k]
        print(f'| {k} | {len(rs)} | {sum(r["runs"] for r in rs)} | {sum(1 for r in rs if r.get("bits"))} | '
              f'{sum(1 for r in rs if "diff" in r and r["diff"] <= 1e-4 * max(1.0, r["size"]))} |')
    print()
    print('| pattern | kind | runs | chemicals | largest \\|value\\| | largest difference from Ready | float vs double |')
    print('|---|---|---|---|---|---|---|')
    for r in rows:
        kind = '%s, %s' % r['kind']
        if 'diff' not in r:
            print(f'| {r["pattern"]} | {kind} | {"yes" if r["runs"] else "no: " + r["error"]} | | | | |')
            continue
        spread = f'{r["spread"]:.2g}' if 'spread' in r else ''
        diff = 'bits' if r.get('bits') else f'{r["diff"]:.2g}'
        print(f'| {r["pattern"]} | {kind} | yes | {r["chemicals"]} | {r["size"]:.3g} | {diff} | {spread} |')


main()
