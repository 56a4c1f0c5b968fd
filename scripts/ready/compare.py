#!/usr/bin/python3
"""figgen against Ready on every pattern file of Ready's repository:
docs/ready-patterns.md's table.

    RDY_BUILD=build-rdy /usr/bin/python3 scripts/ready/compare.py READY/Patterns WORK > docs/ready-patterns.md
    /usr/bin/python3 scripts/ready/compare.py READY/Patterns WORK --report-only   # the table of the rows so far

(build/figgen must not be rebuilt while it runs; FIGGEN=path runs another copy.)

Every .vti and .vtu under Patterns/ is listed with its kind: its rule
(formula, inbuilt, kernel) and its grid (1-D, 2-D, 3-D image, or a mesh).
For each: `figgen render P --set steps=5 --format png` (does it run?);
Ready's start and Ready's 100 steps from it (rdy); figgen's 100 steps
from the same start (--format vti, or vtu for a mesh); the largest
difference. Formula and inbuilt rules on images start from rdy_start
(scripts/ready/run_pattern.sh: the pattern as loaded, its generator
applied); kernel rules and meshes from `rdy -i P -n 1 -o start`, as Ready
saves no state before its first step there. Where the difference exceeds
1e-4 x max(1, largest |value|), how much the pattern amplifies rounding:
for formulas, figgen's run in double against its run in float; for
kernels and meshes (whose kernels name their types), figgen's run from
the start with every value moved by one unit in the last place against
its run from the start itself. Of the same order as the difference from
Ready (at least a third of it): the pattern amplifies rounding, and no
two float implementations agree on it. A pattern's results are kept in
WORK/<pattern>/row.json and Ready's runs in WORK/<pattern>/: a second
pass (or one resumed) reuses them. Reads VTK files with Debian's VTK
(python3-vtk9).
"""
import glob, json, os, re, subprocess, sys, time
import xml.etree.ElementTree as ET
import numpy as np
import vtkmodules.all as vtk
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
FIGGEN = os.environ.get('FIGGEN', os.path.join(HERE, '..', '..', 'build', 'figgen'))
STEPS = 100


def arrays(path):
    """Every chemical array of a .vti (point data) or .vtu (cell data), as doubles."""
    if path.endswith('.vtu'):
        r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(path); r.Update()
        d = r.GetOutput().GetCellData()
    else:
        r = vtk.vtkXMLImageDataReader(); r.SetFileName(path); r.Update()
        d = r.GetOutput().GetPointData()
    out = {}
    for i in range(d.GetNumberOfArrays()):
        name = d.GetArrayName(i)
        if re.fullmatch(r'[a-z]', name or ''):
            out[name] = vtk_to_numpy(d.GetArray(i)).astype(np.float64)
    return out


def perturbed(src, dst):
    """src with every chemical's value one unit in the last place up (of its
    own type), its arrays written as ascii; the rest of the file as it is."""
    values = arrays(src)
    tree = ET.parse(src)
    for a in tree.iter('DataArray'):
        name = a.get('Name')
        if name not in values:
            continue
        f64 = a.get('type') == 'Float64'
        t = np.float64 if f64 else np.float32
        v = values[name].astype(t)
        v = np.where(v != 0, np.nextafter(v, t(np.inf)), v)  # zero stays zero
        a.set('format', 'ascii')
        a.text = ' '.join(repr(float(x)) for x in v)
    tree.write(dst, xml_declaration=True, encoding='utf-8')


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


def ready_runs(path, kind, out):
    """Ready's start and its STEPS steps from it, in `out`; their names, or None."""
    ext = '.vtu' if kind[1] == 'mesh' else '.vti'
    start, last = out + '/start' + ext, out + '/ready%d' % STEPS + ext
    if os.path.exists(start) and os.path.exists(last):
        return start, last
    if kind[0] in ('formula', 'inbuilt') and kind[1] != 'mesh':
        ok = subprocess.run(['bash', os.path.join(HERE, 'run_pattern.sh'), path, out],
                            capture_output=True, text=True).returncode == 0
        return (start, last) if ok else None
    rdy = os.path.join(os.environ['RDY_BUILD'], 'rdy')
    for src, dst, n in ((path, start, 1), (start, last, STEPS)):
        log = subprocess.run([rdy, '-i', src, '-n', str(n), '-o', dst], capture_output=True, text=True, cwd=out)
        if log.returncode or 'Something went wrong' in log.stdout + log.stderr or not os.path.exists(dst):
            return None
    return start, last


def largest(a, b):
    return max(float(np.max(np.abs(a[k] - b[k]))) for k in b)


def compare(path, kind, out):
    row = {}
    runs = ready_runs(path, kind, out)
    if not runs:
        row['note'] = 'rdy could not run it'
        return row
    start, last = runs
    fmt = 'vtu' if kind[1] == 'mesh' else 'vti'
    t = time.time()
    ran = figgen(start, '--set', 'steps=%d' % STEPS, '--format', fmt, '--out', out, '--set', 'id=float')
    row['seconds'] = time.time() - t
    if ran.returncode:
        if not all(np.all(np.isfinite(v)) for v in arrays(start).values()):
            row['note'] = 'Ready\'s own start holds numbers that are not finite: nothing to compare from'
        else:
            row['note'] = 'from Ready\'s start: ' + (ran.stderr.strip().splitlines() or ['?'])[-1]
        return row
    a, b = arrays(out + '/float.' + fmt), arrays(last)
    if set(a) != set(b) or any(a[k].shape != b[k].shape for k in b):
        row['note'] = 'the arrays differ in name or size'
        return row
    if not all(np.all(np.isfinite(b[k])) for k in b):
        row['note'] = 'Ready\'s own state is not finite'
    row['diff'] = largest(a, b)
    row['bits'] = all(np.array_equal(a[k], b[k]) for k in b)
    row['size'] = max(float(np.max(np.abs(b[k]))) for k in b)
    row['chemicals'] = len(b)
    if row['diff'] > 1e-4 * max(1.0, row['size']):
        if kind[0] == 'kernel' or kind[1] == 'mesh':
            perturbed(start, out + '/nudged.' + fmt)
            figgen(out + '/nudged.' + fmt, '--set', 'steps=%d' % STEPS, '--format', fmt, '--out', out,
                   '--set', 'id=other')
        else:
            figgen(start, '--set', 'steps=%d' % STEPS, '--set', 'data_type=double', '--format', fmt,
                   '--out', out, '--set', 'id=other')
        if os.path.exists(out + '/other.' + fmt):
            row['spread'] = largest(a, arrays(out + '/other.' + fmt))
    return row


def tolerance_ok(r):
    return 'diff' in r and r['diff'] <= 1e-4 * max(1.0, r['size'])


def amplifies(r):
    return 'spread' in r and not tolerance_ok(r) and r['spread'] >= r['diff'] / 3


def main():
    patterns, work = sys.argv[1], sys.argv[2]
    report_only = '--report-only' in sys.argv[3:]  # the rows kept so far; the others said not compared
    rows = []
    files = sorted(glob.glob(patterns + '/**/*.vti', recursive=True) + glob.glob(patterns + '/**/*.vtu', recursive=True))
    for path in files:
        kind = kind_of(path)
        rel = os.path.relpath(path, patterns)[:-4]
        out = os.path.join(work, rel)
        os.makedirs(out, exist_ok=True)
        kept = out + '/row.json'
        if os.path.exists(kept):
            row = json.load(open(kept))
        elif report_only:
            row = {'runs': False, 'error': 'not compared yet'}
        else:
            ran = figgen(path, '--set', 'steps=5', '--format', 'png', '--out', out, '--set', 'id=own')
            row = {'runs': ran.returncode == 0,
                   'error': (ran.stderr.strip().splitlines() or ['?'])[-1] if ran.returncode else ''}
            if row['runs']:
                row.update(compare(path, kind, out))
            json.dump(row, open(kept, 'w'))
        row.update({'pattern': rel, 'kind': kind})
        rows.append(row)
        print(rel, row.get('diff'), row.get('note', ''), file=sys.stderr)
    report(rows)


def report(rows):
    agree = [r for r in rows if tolerance_ok(r)]
    bits = [r for r in rows if r.get('bits')]
    print('# Ready\'s patterns in figgen\n')
    print('Made by `scripts/ready/compare.py` (its docstring gives the command) from GollyGang/Ready\'s')
    print('Patterns/ folder: every pattern file, with its kind (the rule: formula, inbuilt or kernel; the')
    print('grid: 1-D, 2-D or 3-D image, or mesh). "Runs": `figgen render P --set steps=5 --format png`')
    print('succeeds. Against Ready: from the same start (Ready\'s own: saved by rdy_start for formula and')
    print('inbuilt rules on images, by `rdy -i P -n 1 -o start` for kernels and meshes), the largest')
    print('difference of any chemical in any cell after 100 steps of figgen and of Ready\'s `rdy` (PoCL 3.1')
    print('on the CPU for formulas and kernels, its own C++ for the inbuilt Gray-Scott), with the largest')
    print('value for scale; "bits" where every value is the same float. figgen runs Ready\'s formulas and')
    print('kernels in Ready\'s OpenCL arithmetic (a * b + c inside one expression is one fused')
    print('multiply-add, as pocl\'s clang contracts it; subnormals flushed to zero); what still differs by')
    print('a unit in the last place comes from OpenCL\'s built-in functions (pocl\'s pow, exp, sin, atan2')
    print('round differently from glibc\'s). Where the difference exceeds 1e-4 x max(1, largest |value|),')
    print('"rounding amplified" is how far two figgen runs are apart whose arithmetic differs at the')
    print('level of rounding: a formula in float and in double; a kernel or mesh pattern from its start and')
    print('from its start with every value moved by one unit in the last place. At least a third of the')
    print('difference from Ready: the pattern amplifies rounding (chaotic dynamics, discrete thresholds,')
    print('divisions by near-zero gradients) and no two float implementations agree on it. docs/kernels.md')
    print('says how kernels and meshes are run.\n')
    kinds = {}
    for r in rows:
        kinds.setdefault('%s, %s' % r['kind'], []).append(r)
    print(f'{len(rows)} pattern files: {sum(r["runs"] for r in rows)} run; {len(bits)} are Ready\'s numbers to the '
          f'bit after 100 steps and {len(agree)} agree within 1e-4 x max(1, largest |value|); '
          f'{sum(1 for r in rows if amplifies(r))} more amplify rounding.\n')
    print('| kind | files | run | to the bit | within 1e-4 of Ready | amplify rounding | other |')
    print('|---|---|---|---|---|---|---|')
    for k in sorted(kinds):
        rs = kinds[k]
        other = sum(1 for r in rs if r['runs'] and not tolerance_ok(r) and not amplifies(r))
        print(f'| {k} | {len(rs)} | {sum(r["runs"] for r in rs)} | {sum(1 for r in rs if r.get("bits"))} | '
              f'{sum(1 for r in rs if tolerance_ok(r))} | {sum(1 for r in rs if amplifies(r))} | {other} |')
    print()
    print('| pattern | kind | runs | chemicals | largest \\|value\\| | largest difference from Ready | '
          'rounding amplified | note |')
    print('|---|---|---|---|---|---|---|---|')
    for r in rows:
        kind = '%s, %s' % r['kind']
        note = r.get('note', '')
        if 'diff' not in r:
            print(f'| {r["pattern"]} | {kind} | {"yes" if r["runs"] else "no: " + r["error"]} | | | | | {note} |')
            continue
        spread = f'{r["spread"]:.2g}' if 'spread' in r else ''
        diff = 'bits' if r.get('bits') else f'{r["diff"]:.2g}'
        print(f'| {r["pattern"]} | {kind} | yes | {r["chemicals"]} | {r["size"]:.3g} | {diff} | {spread} | {note} |')


main()
