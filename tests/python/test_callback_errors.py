"""A progress callback that raises, and a process that exits right after:
the exception comes back as raised, nothing is freed twice, nothing hangs.
Run by ctest in the normal build and, under AddressSanitizer, in
`make test-sanitize` (tests/CMakeLists.txt)."""

import json
import os
import re
import subprocess
import sys
import textwrap
import threading

import pytest

import figgen

# What a process that freed something twice, or aborted, leaves on stderr:
# glibc's words, ASan's, and libstdc++'s for an exception that escaped.
CRASHED = re.compile(r"double free|free\(\)|corruption|munmap_chunk|AddressSanitizer|LeakSanitizer|runtime error:|"
                     r"terminate called|Aborted|Segmentation fault")

# One process: tc7-1 (16 steps, at half size) whose callback raises at call
# `at`, then the process's exit, at once. It prints what it caught.
RAISE_AT = textwrap.dedent("""
    import json, os, sys
    import figgen

    class Raised(Exception):
        pass

    at, out, kind = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    raised, calls = [], []

    def report(done, total, label):
        calls.append([done, total, label])
        if len(calls) == at + 1:
            raised.append(Raised(f"at call {at}") if kind == "Raised" else KeyboardInterrupt(f"at call {at}"))
            raise raised[0]

    try:
        figgen.render("tc7-1", scale=0.5, out=out, progress=report)
        print(json.dumps({"caught": None}))
    except BaseException as e:
        print(json.dumps({"caught": type(e).__name__, "message": str(e), "itself": e is raised[0],
                          "calls": calls, "files": sorted(os.listdir(out)) if os.path.isdir(out) else []}))
""")


def calls_of_a_render():
    seen = []
    figgen.render("tc7-1", scale=0.5, progress=lambda done, total, label: seen.append((done, total, label)))
    return seen


def raise_at(at, out, kind="Raised"):
    """Runs RAISE_AT in a process of its own: (exit status, what it printed, its stderr)."""
    run = subprocess.run([sys.executable, "-c", RAISE_AT, str(at), str(out), kind], capture_output=True, text=True,
                         timeout=120)  # a hang fails here
    return run.returncode, json.loads(run.stdout) if run.stdout.strip() else None, run.stderr


def test_the_stages_a_callback_sees():
    """start (0 of 16), each step's advance, finish (16 of 16): the calls the tests below raise at."""
    seen = calls_of_a_render()
    assert seen == [(done, 16, "tc7-1") for done in range(17)]


# The stages: start, the first advances, one in the middle, the last advance
# and finish (every advance is the same call of the step loop; the race at
# exit is the test after next's, 20 runs).
@pytest.mark.parametrize("at", [0, 1, 2, 8, 15, 16],
                         ids=lambda at: "start" if at == 0 else "finish" if at == 16 else f"advance {at}")
def test_a_callback_raising_at_each_stage_raises_as_itself_and_the_process_exits_cleanly(at, tmp_path):
    status, printed, stderr = raise_at(at, tmp_path / "out")
    assert not CRASHED.search(stderr), stderr
    assert status == 0, stderr
    assert printed["caught"] == "Raised" and printed["message"] == f"at call {at}" and printed["itself"]
    assert len(printed["calls"]) == at + 1  # the render stopped there: no call after the one that raised
    assert printed["files"] == []  # and wrote nothing


def test_a_callback_raising_early_again_and_again(tmp_path):
    """The race this guards against: a render stopped before it needed GL, the process's exit while GL's
    loader was still inside dlopen, and LLVM's static objects destroyed twice, about one run in twenty
    (one in four under ASan). Raising at the first calls: fifty runs under the sanitizers, where the race
    shows most (FIGGEN_RACE_RUNS, tests/CMakeLists.txt), twenty in the plain build."""
    for run in range(int(os.environ.get("FIGGEN_RACE_RUNS", "20"))):
        status, printed, stderr = raise_at(run % 5, tmp_path / "out")
        assert not CRASHED.search(stderr), f"run {run}: {stderr}"
        assert status == 0 and printed["caught"] == "Raised" and printed["itself"], f"run {run}: {stderr}"


def test_a_keyboard_interrupt_raised_by_the_callback_comes_back_as_itself(tmp_path):
    for at in (0, 16):
        status, printed, stderr = raise_at(at, tmp_path / "out", "KeyboardInterrupt")
        assert not CRASHED.search(stderr), stderr
        assert status == 0 and printed["caught"] == "KeyboardInterrupt" and printed["message"] == f"at call {at}"
        assert printed["itself"] and printed["files"] == []


def test_the_exception_keeps_its_traceback_and_the_process_renders_on(tmp_path):
    class Raised(Exception):
        pass

    error = Raised("from the callback")

    def report(done, total, label):
        if done == 3:
            raise error

    with pytest.raises(Raised) as caught:
        figgen.render("tc7-1", scale=0.5, out=tmp_path, progress=report)
    assert caught.value is error
    # The callback's own line is in the traceback, under render()'s.
    assert any(frame.name == "report" for frame in caught.traceback)
    assert list(tmp_path.iterdir()) == []
    assert figgen.render("tc7-1", scale=0.5, out=tmp_path).paths[0] == tmp_path / "tc7-1.png"


def test_a_render_asked_for_inside_a_callback_is_refused_not_waited_for():
    """It would wait for the render thread, which waits for the callback: a hang."""
    inner = []

    def report(done, total, label):
        if done == 1:
            try:
                figgen.render("tc7-1", scale=0.5)
            except figgen.RenderError as e:
                inner.append(e)
                raise

    with pytest.raises(figgen.RenderError) as caught:
        figgen.render("tc7-1", scale=0.5, progress=report)
    assert caught.value is inner[0]
    assert str(caught.value) == ("render() was called from a progress callback: a process renders one figure at a "
                                 "time, and this one waits for its callback")


DAEMON = textwrap.dedent("""
    import sys, threading, time
    import figgen

    calls = []
    def work():
        try:
            figgen.render("tc7-2", set={"n": 256}, progress=lambda *a: calls.append(a))
        except BaseException as e:
            # One write: print() writes its words one by one, and Python may
            # freeze this daemon thread between two of them once it exits.
            sys.stdout.write(f"{type(e).__name__} {e}\\n")
            sys.stdout.flush()

    threading.Thread(target=work, daemon=True).start()
    while len(calls) < int(sys.argv[1]):
        time.sleep(0.01)
    print("exit", flush=True)
""")


@pytest.mark.parametrize("calls", [1, 5])
def test_an_exit_while_a_daemon_thread_renders_stops_the_render_first(calls):
    """Python finalizes only once no render can call into it."""
    run = subprocess.run([sys.executable, "-c", DAEMON, str(calls)], capture_output=True, text=True, timeout=120)
    assert not CRASHED.search(run.stderr), run.stderr
    assert run.returncode == 0, run.stderr
    # The daemon thread may or may not get to say why its render ended before Python stops it.
    lines = run.stdout.splitlines()
    assert lines[0] == "exit" and lines[1:] in ([], ["RenderError stopped: Python is exiting"]), lines


def test_renders_from_two_threads_with_raising_callbacks():
    """Each render's error goes to its own caller."""
    results = {}

    def render(name, at):
        def report(done, total, label):
            if done == at:
                raise ValueError(name)

        try:
            figgen.render("tc7-1", scale=0.5, progress=report)
        except ValueError as e:
            results[name] = str(e)

    threads = [threading.Thread(target=render, args=(f"thread {i}", i + 2)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == {"thread 0": "thread 0", "thread 1": "thread 1"}
