"""Times the book's own route through Think Complexity 2e, chapter 7.

figgen's C++ benchmark reports speed ratios against the method the book
teaches: NumPy arrays stepped with scipy.signal.correlate2d and drawn with
matplotlib (Allen Downey's Cell1D.py, Cell2D.py and chap07 notebook). This
script re-creates that code in the book's style and times, on this machine:
  - Gray-Scott steps (ReactionDiffusion.step) at n = 100, 256, 1024;
  - percolation: test_perc at n=100, q=0.6, and find_critical(n=100);
  - each of the nine printed figures, model and plt.savefig together;
  - tc7-2's film as a reader of the book would make it: every 20th step of
    the book's update from 0 to 7000 drawn as the book draws (A in Reds, B in
    Blues, alpha 0.7, bicubic, no ticks, a title with the step) on a 4.8 x 5.2
    inch figure at 100 dpi, through matplotlib.animation.FFMpegWriter
    (libx264, yuv420p, crf 18) and Debian's ffmpeg; skipped without ffmpeg.

    /usr/bin/python3 bench/book_peer.py --out DIR [--quick]

writes DIR/peer.json, DIR/book-figures/tc7-1.png .. tc7-9.png and
DIR/book-figures/tc7-2.mp4. Without
numpy, scipy or matplotlib it writes {"skipped": reason} and exits 0, so the
C++ side can report that no ratio was measured. Progress goes to stderr.
"""
import argparse
import importlib.util
import json
import os
import statistics
import sys
import time

START = time.perf_counter()
PACKAGES = {"numpy": "python3-numpy", "scipy": "python3-scipy",
            "matplotlib": "python3-matplotlib"}
INSTALL = "apt-get install " + " ".join(PACKAGES.values())

# Work per timing. Full: each Gray-Scott repeat takes ~1 s, find_critical
# (~7 s) runs once, the whole run stays under a minute; quick is a smoke test.
PROFILES = {
    "full": dict(repeats=3, gs_steps={100: 1500, 256: 200, 1024: 10}, perc_runs=20,
                 crit_iters=100, crit_repeats=1, rd_loops=(1000, 2000, 4000),
                 scaling_sizes=range(10, 101), film_steps=7000),
    "quick": dict(repeats=1, gs_steps={100: 20, 256: 5, 1024: 1}, perc_runs=3,
                  crit_iters=10, crit_repeats=1, rd_loops=(100, 200, 400),
                  scaling_sizes=range(10, 101, 10), film_steps=200),
}


def log(msg):
    print("book_peer: " + msg, file=sys.stderr, flush=True)


def write_json(out, data):
    """Writes DIR/peer.json through a temporary name, so readers never see half a file."""
    tmp = os.path.join(out, "peer.json.tmp")
    with open(tmp, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    os.replace(tmp, os.path.join(out, "peer.json"))


def import_book_libraries():
    """Imports the book's libraries as globals; returns the missing Debian packages.

    Imported here, not at the top, so that the script still runs, and says
    what to install, on a Python without them.
    """
    missing = [pkg for mod, pkg in PACKAGES.items() if importlib.util.find_spec(mod) is None]
    if missing:
        return missing
    global np, plt, mpl, scipy, correlate2d, linregress
    import matplotlib as mpl
    mpl.use("Agg")  # no display on the benchmark machine
    import matplotlib.pyplot as plt
    import numpy as np
    import scipy
    from scipy.signal import correlate2d
    from scipy.stats import linregress
    mpl.rcParams["lines.linewidth"] = 2.0  # as the book's utils.py sets it
    return []


# ---- the book's code (Cell2D.py, Cell1D.py, utils.py, chap07) ----
# Line for line as published, minus docstrings, so the timings are the book's.

def underride(d, **options):
    for key, val in options.items():
        d.setdefault(key, val)
    return d


def draw_array(array, **options):
    n, m = array.shape
    options = underride(options, cmap="Greens", alpha=0.7, vmin=0, vmax=1,
                        interpolation="none", origin="upper", extent=[0, m, 0, n])
    plt.axis([0, m, 0, n])
    plt.xticks([])
    plt.yticks([])
    return plt.imshow(array, **options)


def decorate(loc="best", **options):
    handles, labels = plt.gca().get_legend_handles_labels()
    if handles:
        plt.gca().legend(handles, labels, loc=loc, frameon=False)
    plt.gca().set(**options)
    plt.tight_layout()


def three_frame(world, n_seq, seed=17):
    np.random.seed(seed)
    plt.figure(figsize=(10, 4))
    for i, n in enumerate(n_seq):
        plt.subplot(1, 3, i + 1)
        world.loop(n)
        world.draw()
    plt.tight_layout()


def add_island(a, height=0.1):
    n, m = a.shape
    radius = min(n, m) // 20
    i, j = n // 2, m // 2
    a[i - radius:i + radius, j - radius:j + radius] += height


class Cell2D:
    def loop(self, iters=1):
        for _ in range(iters):
            self.step()


class Diffusion(Cell2D):
    kernel = None  # the kernels are set by make_kernels, once numpy is imported

    def __init__(self, n, r=0.1):
        self.r = r
        self.array = np.zeros((n, n), float)

    def add_cells(self, row, col, *strings):
        for i, s in enumerate(strings):
            self.array[row + i, col:col + len(s)] = np.array([int(b) for b in s])

    def step(self):
        c = correlate2d(self.array, self.kernel, mode="same")
        self.array += self.r * c

    def draw(self):
        draw_array(self.array, cmap="Reds")


class ReactionDiffusion(Diffusion):
    def __init__(self, n, params, noise=0.1):
        self.params = params
        self.array1 = np.ones((n, n), dtype=float)
        self.array2 = noise * np.random.random((n, n))
        add_island(self.array2)

    def step(self):
        A, B = self.array1, self.array2
        ra, rb, f, k = self.params
        options = dict(mode="same", boundary="wrap")
        cA = correlate2d(A, self.kernel, **options)
        cB = correlate2d(B, self.kernel, **options)
        reaction = A * B**2
        self.array1 += ra * cA - reaction + f * (1 - A)
        self.array2 += rb * cB + reaction - (f + k) * B

    def draw(self):
        options = dict(interpolation="bicubic", vmin=None, vmax=None)
        draw_array(self.array1, cmap="Reds", **options)
        draw_array(self.array2, cmap="Blues", **options)


class Percolation(Cell2D):
    def __init__(self, n, q=0.5):
        self.q = q
        self.array = np.random.choice([1, 0], (n, n), p=[q, 1 - q])
        self.array[0] = 5
        self.steps = 0  # not in the book: counts steps for "mean_steps"

    def step(self):
        a = self.array
        c = correlate2d(a, self.kernel, mode="same")
        self.array[(a == 1) & (c >= 5)] = 5
        self.steps += 1

    def num_wet(self):
        return np.sum(self.array == 5)

    def bottom_row_wet(self):
        return np.sum(self.array[-1] == 5)

    def draw(self):
        draw_array(self.array, cmap="Blues", vmax=5)


def make_kernels():
    Diffusion.kernel = np.array([[0, 1, 0], [1, -4, 1], [0, 1, 0]])
    ReactionDiffusion.kernel = np.array([[.05, .2, .05], [.2, -1, .2], [.05, .2, .05]])
    Percolation.kernel = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]])


def test_perc(perc):
    num_wet = perc.num_wet()
    while True:
        perc.step()
        if perc.bottom_row_wet():
            return True
        new_num_wet = perc.num_wet()
        if new_num_wet == num_wet:
            return False
        num_wet = new_num_wet


def find_critical(n=100, q=0.6, iters=100):
    qs = [q]
    for _ in range(iters):
        perc = Percolation(n, q)
        if test_perc(perc):
            q -= 0.005
        else:
            q += 0.005
        qs.append(q)
    return qs


class Cell1D:
    def __init__(self, rule, n):
        self.table = np.unpackbits(np.array([rule], dtype=np.uint8))[::-1]
        self.n, self.m = n, 2 * n + 1
        self.array = np.zeros((n, self.m), dtype=np.int8)
        self.next = 0

    def start_single(self):
        self.array[0, self.m // 2] = 1
        self.next += 1

    def loop(self, steps=1):
        for _ in range(steps):
            self.step()

    def step(self):
        a, i = self.array, self.next
        c = np.correlate(a[i - 1], [4, 2, 1], mode="same")
        a[i] = self.table[c]
        self.next += 1

    def draw(self):
        plt.imshow(self.array, cmap="Blues", alpha=0.7)
        plt.xticks([])
        plt.yticks([])


def draw_ca(rule, n=32):
    ca = Cell1D(rule, n)
    ca.start_single()
    ca.loop(n - 1)
    ca.draw()


def count_cells(rule, n=500):
    ca = Cell1D(rule, n)
    ca.start_single()
    res = []
    for i in range(1, n):
        res.append((i, i**2, np.sum(ca.array)))
        ca.step()
    return res


def test_fractal(rule, ylabel="Number of Cells"):
    steps, steps2, cells = zip(*count_cells(rule))
    options = dict(linestyle="dashed", color="gray", alpha=0.7)
    plt.plot(steps, steps2, label="d=2", **options)
    plt.plot(steps, cells, label="rule=%d" % rule)
    plt.plot(steps, steps, label="d=1", **options)
    decorate(xscale="log", yscale="log", xlabel="Time Steps", ylabel=ylabel,
             xlim=[1, 600], loc="upper left")
    return linregress(np.log(steps), np.log(cells))[0]


def run_perc_scaling(sizes, q):
    res = []
    for size in sizes:
        perc = Percolation(size, q)
        if test_perc(perc):
            res.append((size, size**2, perc.num_wet() - size))
    return np.transpose(res)


def plot_perc_scaling(sizes, cells, filled):
    options = dict(linestyle="dashed", color="gray", alpha=0.7)
    plt.plot(sizes, cells, label="d=2", **options)
    plt.plot(sizes, filled, ".", label="filled")
    plt.plot(sizes, sizes, label="d=1", **options)
    decorate(xlabel="Array Size", ylabel="Cell Count", xscale="log", xlim=[9, 110],
             yscale="log", ylim=[9, 20000], loc="upper left")
    return linregress(np.log(sizes), np.log(filled))[0]


# ---- the nine printed figures, as the notebook makes them ----

def fig_diffusion(p):
    diff = Diffusion(n=9, r=0.1)
    diff.add_cells(3, 3, "111", "111", "111")
    three_frame(diff, [0, 5, 10])


def fig_rd(f, k):
    def make(p):
        three_frame(ReactionDiffusion(100, (0.5, 0.25, f, k)), p["rd_loops"])
    return make


def fig_perc_steps(p):
    np.random.seed(18)
    three_frame(Percolation(10, 0.7), [1, 1, 1])


def fig_three(draw_panel, args):
    plt.figure(figsize=(10, 4))
    for i, arg in enumerate(args):
        plt.subplot(1, 3, i + 1)
        draw_panel(i, arg)
    plt.tight_layout()


def fig_cas(p):
    fig_three(lambda i, rule: draw_ca(rule), [20, 50, 18])


def fig_cell_counts(p):
    def panel(i, rule):
        log("  rule %d slope %.3f" % (rule, test_fractal(rule, "" if i else "Number of Cells")))
    fig_three(panel, [20, 50, 18])


def fig_perc_sizes(p):
    def panel(i, n):
        np.random.seed(22)
        perc = Percolation(n, 0.6)
        test_perc(perc)
        perc.draw()
    fig_three(panel, [100, 200, 300])


def fig_scaling(p):
    np.random.seed(17)
    plt.figure()
    log("  cluster slope %.3f" % plot_perc_scaling(*run_perc_scaling(p["scaling_sizes"], 0.59)))


FIGURES = {"tc7-1": fig_diffusion, "tc7-2": fig_rd(0.035, 0.057),
           "tc7-3": fig_rd(0.055, 0.062), "tc7-4": fig_rd(0.039, 0.065),
           "tc7-5": fig_perc_steps, "tc7-6": fig_cas, "tc7-7": fig_cell_counts,
           "tc7-8": fig_perc_sizes, "tc7-9": fig_scaling}


# ---- timings ----

def median_time(work, repeats, seed):
    """Median wall time of work(); reseeding makes every repeat do identical work."""
    times = []
    for _ in range(repeats):
        np.random.seed(seed)
        t0 = time.perf_counter()
        result = work()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), result


def time_rd_steps(n, steps, seed=17):
    """Seconds for rd.loop(steps); setup is not a step, so it is left out."""
    np.random.seed(seed)
    rd = ReactionDiffusion(n, (0.5, 0.25, 0.035, 0.057))
    t0 = time.perf_counter()
    rd.loop(steps)
    return time.perf_counter() - t0


def time_gray_scott(p):
    rows = []
    for n, steps in p["gs_steps"].items():
        times = [time_rd_steps(n, steps) for _ in range(p["repeats"])]
        per_step = statistics.median(times) / steps
        rows.append({"n": n, "steps": steps, "seconds_per_step": per_step,
                     "cell_updates_per_second": n * n / per_step, "repeats": p["repeats"]})
        log("gray_scott n=%d: %.3g s/step" % (n, per_step))
    return rows


def time_percolation(p):
    runs = p["perc_runs"]

    def batch():
        percs = [Percolation(100, 0.6) for _ in range(runs)]
        for perc in percs:
            test_perc(perc)
        return percs
    seconds, percs = median_time(batch, p["repeats"], 18)
    test = {"n": 100, "q": 0.6, "runs": runs, "seconds_per_run": seconds / runs,
            "mean_steps": statistics.mean(perc.steps for perc in percs),
            "repeats": p["repeats"]}
    log("test_perc: %.3g s/run" % test["seconds_per_run"])
    iters = p["crit_iters"]
    repeats = p["crit_repeats"]
    seconds, qs = median_time(lambda: find_critical(100, 0.6, iters), repeats, 1)
    crit = {"n": 100, "iterations": iters, "seconds": seconds,
            "estimate": float(np.mean(qs)), "repeats": repeats}
    log("find_critical: %.3g s, q_crit ~ %.4f" % (seconds, crit["estimate"]))
    return {"test_perc": test, "find_critical": crit}


def time_figures(p, fig_dir):
    per_figure = {}
    for fig_id, make in FIGURES.items():
        t0 = time.perf_counter()
        make(p)
        plt.savefig(os.path.join(fig_dir, fig_id + ".png"))
        per_figure[fig_id] = time.perf_counter() - t0
        plt.close("all")
        log("%s: %.2f s" % (fig_id, per_figure[fig_id]))
    return {"seconds": sum(per_figure.values()), "per_figure": per_figure}


def time_film(p, fig_dir, stride=20, fps=30):
    """tc7-2's film the book reader's way: model, drawing and encoding together."""
    import shutil
    from matplotlib.animation import FFMpegWriter
    if shutil.which("ffmpeg") is None:
        log("film: skipped: no ffmpeg (apt-get install ffmpeg)")
        return {"skipped": "no ffmpeg (apt-get install ffmpeg)"}
    np.random.seed(17)  # as three_frame seeds tc7-2
    rd = ReactionDiffusion(100, (0.5, 0.25, 0.035, 0.057))
    fig = plt.figure(figsize=(4.8, 5.2), dpi=100)
    writer = FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt", "yuv420p", "-crf", "18"])
    path = os.path.join(fig_dir, "tc7-2.mp4")
    frames = 0
    t0 = time.perf_counter()
    with writer.saving(fig, path, dpi=100):
        for step in range(p["film_steps"] + 1):
            if step % stride == 0:
                fig.clf()
                rd.draw()
                plt.title("step %d" % step)
                writer.grab_frame()
                frames += 1
            if step < p["film_steps"]:
                rd.step()
    seconds = time.perf_counter() - t0
    plt.close(fig)
    log("film tc7-2: %d frames in %.2f s" % (frames, seconds))
    return {"seconds": seconds, "frames": frames, "steps": p["film_steps"], "stride": stride, "fps": fps,
            "size": [480, 520], "bytes": os.path.getsize(path)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help="directory for peer.json and book-figures/")
    parser.add_argument("--quick", action="store_true", help="small smoke-test run")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    missing = import_book_libraries()
    if missing:
        reason = "missing Debian package(s) %s (install with: %s)" % (" ".join(missing), INSTALL)
        print("book_peer: skipped: " + reason, file=sys.stderr)
        write_json(args.out, {"skipped": reason})
        return
    make_kernels()
    p = PROFILES["quick" if args.quick else "full"]
    fig_dir = os.path.join(args.out, "book-figures")
    os.makedirs(fig_dir, exist_ok=True)
    result = {"versions": {"python": sys.version.split()[0], "numpy": np.__version__,
                           "scipy": scipy.__version__, "matplotlib": mpl.__version__}}
    result["gray_scott"] = time_gray_scott(p)
    result["percolation"] = time_percolation(p)
    result["tc7_figures"] = time_figures(p, fig_dir)
    result["tc7_2_film"] = time_film(p, fig_dir)
    result["total_seconds"] = time.perf_counter() - START
    write_json(args.out, result)
    log("done in %.1f s" % result["total_seconds"])


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # one line for the C++ side, not a traceback
        print("book_peer: error: %s: %s" % (type(e).__name__, e), file=sys.stderr)
        sys.exit(1)
