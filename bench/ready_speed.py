#!/usr/bin/python3
"""figgen beside Ready's own rdy on the same Gray-Scott formula, whole process
(`make bench` runs it; it says so and stops when there is no rdy).

    /usr/bin/python3 bench/ready_speed.py build/figgen [RDY] > bench/results/ready.json

RDY is Ready's command-line tool (scripts/ready/CMakeLists.txt builds it;
default: $RDY, else build-rdy/rdy). Each start is a VTI file figgen writes
at step 0 (Pearson's Gray-Scott, F = 0.037, k = 0.06, as Ready's
GrayScott1984/Pearson1993.vti, from a square of noise): 64 x 64, 128 x 64, 256 x 256,
1024 x 1024 and 128^3 cells. Both tools run N steps from it, as a whole process: figgen
`render START.vti --set steps=N --format vti` (it writes its figure and the
last step too), rdy `-i START.vti -n N -o OUT.vti`. The median of three
runs of each, taken in turn; the ratio is figgen's time over rdy's.

Then, where READY_PATTERNS names Ready's Patterns/ folder, kernel rules and
meshes (docs/kernels.md): SmoothLife (smoothlifeL, smoothglider), Life on a
Penrose tiling and on a torus, Gray-Scott on the bunny. Each starts from
Ready's own state after one step (`rdy -i P -n 1 -o START`); both tools run
N steps from it as above (figgen's --format vti or vtu); cell-updates per
second are cells x N over the whole process's time.
"""
import json, os, statistics, subprocess, sys, tempfile, time

FORMULA = '''delta_a = D_a * laplacian_a - a*b*b + F*(1.0f-a);
delta_b = D_b * laplacian_b + a*b*b - (F+K)*b;
'''


def description(width, height, depth):
    return f'''id = "start"
title = "Pearson's Gray-Scott"
scene = "formula"
seed = 1
[params]
chemicals = 2
formula = """{FORMULA}"""
width = {width}
height = {height}
depth = {depth}
steps = 0
timestep = 1.0
D_a = 0.2
D_b = 0.1
F = 0.037
K = 0.06
[[params.initial]]
chemical = "a"
fill = "constant"
value = 1.0
shapes = [{{shape = "everywhere"}}]
[[params.initial]]
chemical = "b"
fill = "white_noise"
low = 0.0
high = 0.5
shapes = [{{shape = "rectangle", from = [0.4, 0.4, 0.4], to = [0.6, 0.6, 0.6]}}]
[style]
show = ["b"]
[figure]
panels = [0]
size = [{960 if depth > 1 else 600}, 480]
'''


def timed(command):
    t = time.monotonic()
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode:
        raise SystemExit(' '.join(command) + ' failed: ' + run.stderr.strip()[-300:])
    return time.monotonic() - t


def main():
    figgen = sys.argv[1]
    rdy = sys.argv[2] if len(sys.argv) > 2 else os.environ.get('RDY', 'build-rdy/rdy')
    if not os.access(rdy, os.X_OK):
        print(f'ready_speed: no rdy at {rdy} (scripts/ready/CMakeLists.txt builds it): skipped', file=sys.stderr)
        print(json.dumps({'skipped': 'no rdy'}))
        return
    cases = [('64 x 64', 64, 64, 1, 100000), ('128 x 64', 128, 64, 1, 60000), ('256 x 256', 256, 256, 1, 20000),
             ('1024 x 1024', 1024, 1024, 1, 1500), ('128^3', 128, 128, 128, 300)]
    results = []
    with tempfile.TemporaryDirectory() as work:
        for name, w, h, d, steps in cases:
            desc = os.path.join(work, 'start.toml')
            with open(desc, 'w') as f:
                f.write(description(w, h, d))
            out = os.path.join(work, name.replace(' ', '').replace('^', ''))
            subprocess.run([figgen, 'render', desc, '--format', 'vti', '--out', out], check=True, capture_output=True)
            start = os.path.join(out, 'start.vti')
            ours, theirs = [], []
            for _ in range(3):
                ours.append(timed([figgen, 'render', start, '--set', f'steps={steps}', '--set', 'id=figgen',
                                   '--format', 'vti', '--out', out]))
                theirs.append(timed([rdy, '-i', start, '-n', str(steps), '-o', os.path.join(out, 'rdy.vti')]))
            a, b = statistics.median(ours), statistics.median(theirs)
            results.append({'grid': name, 'steps': steps, 'figgen_s': round(a, 3), 'rdy_s': round(b, 3),
                            'figgen_over_rdy': round(a / b, 3)})
            print(f'{name:>10}: {steps} steps, figgen {a:.2f} s, rdy {b:.2f} s, ratio {a / b:.2f}', file=sys.stderr)
    kernels = kernel_cases(figgen, rdy)
    print(json.dumps({'cases': results, 'kernels': kernels}, indent=2))


# (pattern under Patterns/, steps): rdy takes one to a few seconds on 2 cores
KERNELS = [('SmoothLife2011/smoothlifeL.vti', 100), ('SmoothLife2011/smoothglider.vti', 100),
           ('CellularAutomata/PenroseTilings/life.vtu', 10000), ('CellularAutomata/life_torus.vtu', 10000),
           ('GrayScott1984/bunny.vtu', 2000)]


def cells_of(path):
    import vtkmodules.all as vtk
    if path.endswith('.vtu'):
        r = vtk.vtkXMLUnstructuredGridReader()
    else:
        r = vtk.vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    out = r.GetOutput()
    return out.GetNumberOfCells() if path.endswith('.vtu') else out.GetNumberOfPoints()


def kernel_cases(figgen, rdy):
    patterns = os.environ.get('READY_PATTERNS')
    if not patterns:
        print('ready_speed: READY_PATTERNS (Ready\'s Patterns/ folder) not given: kernels and meshes skipped',
              file=sys.stderr)
        return []
    results = []
    with tempfile.TemporaryDirectory() as work:
        for rel, steps in KERNELS:
            ext = rel[-4:]
            start = os.path.join(work, 'start' + ext)
            timed([rdy, '-i', os.path.join(patterns, rel), '-n', '1', '-o', start])
            cells = cells_of(start)
            ours, theirs = [], []
            for _ in range(3):
                ours.append(timed([figgen, 'render', start, '--set', f'steps={steps}', '--set', 'id=figgen',
                                   '--format', ext[1:], '--out', work]))
                theirs.append(timed([rdy, '-i', start, '-n', str(steps), '-o', os.path.join(work, 'rdy' + ext)]))
            a, b = statistics.median(ours), statistics.median(theirs)
            results.append({'pattern': rel, 'cells': cells, 'steps': steps, 'figgen_s': round(a, 3),
                            'rdy_s': round(b, 3), 'figgen_cell_updates_per_s': round(cells * steps / a),
                            'rdy_cell_updates_per_s': round(cells * steps / b), 'figgen_over_rdy': round(a / b, 3)})
            print(f'{rel:>42}: {cells} cells, {steps} steps, figgen {a:.2f} s ({cells * steps / a:.3g}/s), '
                  f'rdy {b:.2f} s ({cells * steps / b:.3g}/s), ratio {a / b:.2f}', file=sys.stderr)
    return results


main()
