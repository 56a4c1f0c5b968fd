"""figgen's Python module, run by pytest through ctest (tests/CMakeLists.txt):
the API, errors with their keys, interrupts, threads, and the command's bits."""

import hashlib
import json
import os
import pathlib
import subprocess
import threading
import time
import tomllib
import _thread

import pytest

import figgen

FIGGEN = os.environ["FIGGEN_EXE"]
FIGURES = pathlib.Path(os.environ["FIGGEN_FIGURES"])
GOLDEN = pathlib.Path(__file__).parent.parent / "golden"


def command(*args):
    return subprocess.run([FIGGEN, *args], capture_output=True, text=True)


def test_catalog_lists_every_description_with_its_title():
    catalog = figgen.catalog()
    assert set(catalog) == {p.stem for p in FIGURES.glob("*.toml")}
    # The titles `figgen list` prints, in its order.
    listed = [line.split(None, 1) for line in command("list").stdout.splitlines()]
    assert [(i, t.strip()) for i, t in listed] == list(catalog.items())


def test_describe_gives_values_defaults_ranges_and_meanings():
    d = figgen.describe("tc7-1")
    assert (d["id"], d["scene"], d["seed"]) == ("tc7-1", "diffusion", 0)
    params = {k["key"]: k for k in d["settings"]["params"]}
    assert params["n"]["value"] == 9
    assert params["r"]["value"] == pytest.approx(0.1)
    assert params["r"]["allowed"] == "from 0 to 0.25"  # the model's own check, sim/diffusion.cpp
    assert params["boundary"]["allowed"] == '"zero" or "wrap"'
    assert params["boundary"]["default"] == "zero"
    style = {k["key"]: k for k in d["settings"]["style"]}
    assert style["alpha"]["value"] == pytest.approx(0.8) and style["alpha"]["default"] == pytest.approx(0.7)
    assert style["vmin"]["value"] == 0
    assert "figure" in d["settings"] and "animation" in d["settings"]


def test_render_writes_the_figure_and_its_metadata(tmp_path):
    fig = figgen.render("tc7-7", out=tmp_path)
    assert fig.metadata["id"] == "tc7-7"
    assert fig.png.startswith(b"\x89PNG\r\n\x1a\n")
    assert [p.name for p in fig.paths] == ["tc7-7.png", "tc7-7.json"]
    assert fig.film is None
    assert fig._repr_png_() == fig.png and fig._repr_html_() is None
    assert (tmp_path / "tc7-7.png").read_bytes() == fig.png


def test_pixels_are_the_png_as_height_by_width_by_four():
    numpy = pytest.importorskip("numpy")
    fig = figgen.render("tc7-1", scale=0.5)
    width, height = fig.metadata["image"]["size"]
    assert fig.pixels.shape == (height, width, 4) and fig.pixels.dtype == numpy.uint8
    # The top-left pixel is the page's white, the block's middle tc7-1's measured red (docs/catalog.md).
    assert tuple(fig.pixels[0, 0]) == (255, 255, 255, 255)


def test_a_changed_parameter_and_a_description_given_in_python():
    changed = figgen.render("tc7-1", set={"r": 0.2, "style.alpha": 0.5}, scale=0.5)
    assert changed.metadata["params"]["r"] == pytest.approx(0.2)
    assert changed.metadata["style"]["alpha"] == pytest.approx(0.5)
    text = (FIGURES / "tc7-1.toml").read_text()
    from_text = figgen.render(text, scale=0.5)
    assert from_text.png == figgen.render("tc7-1", scale=0.5).png
    as_dict = figgen.render({"id": "mine", "scene": "diffusion", "params": {"n": 12, "r": 0.2},
                             "figure": {"panels": [0, 3], "size": [400, 200]}}, scale=0.5)
    assert as_dict.metadata["id"] == "mine" and as_dict.metadata["params"]["n"] == 12


def test_a_temporary_folder_goes_with_its_figure():
    fig = figgen.render("tc7-1", scale=0.5)
    folder = fig.paths[0].parent
    assert folder.is_dir()
    del fig
    assert not folder.exists()


def test_a_film_shows_as_a_video(tmp_path):
    fig = figgen.render("tc7-1", out=tmp_path, formats=("png", "mp4"), scale=0.5)
    assert fig.film == tmp_path / "tc7-1.mp4"
    assert fig._repr_html_().startswith("<figure><video ") and "data:video/mp4;base64," in fig._repr_html_()


def test_a_bad_setting_is_a_setting_error_with_its_key():
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", set={"r": 0.5})
    e = caught.value
    assert isinstance(e, ValueError)
    assert (e.key, e.value) == ("params.r", "0.5")
    assert e.allowed.startswith("a number from 0 to 0.25")
    assert e.where == "set=r=0.5"
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", set={"style.sampling": "blurred"})
    assert caught.value.key == "style.sampling" and caught.value.allowed == '"nearest" or "smooth"'


def test_a_bad_description_names_its_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('scene = "diffusion"\n[params]\nn = 9\nr = -1\n')
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render(bad)
    assert caught.value.key == "params.r" and caught.value.where == "bad.toml:4"  # as figgen names files
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("no-such-figure")
    assert caught.value.key is None and "no-such-figure" in str(caught.value)


def test_a_run_that_goes_unstable_is_a_render_error_and_writes_nothing(tmp_path):
    with pytest.raises(figgen.RenderError) as caught:
        figgen.render("tc7-2", out=tmp_path, set={"n": 20, "ra": 1, "rb": 1, "f": 0.2, "k": 0, "noise": 1, "island": 1})
    assert "went numerically unstable at step 2" in str(caught.value)
    assert list(tmp_path.iterdir()) == []


def test_progress_reaches_a_callable_and_a_tqdm_like_bar():
    seen = []
    figgen.render("tc7-1", scale=0.5, progress=lambda done, total, label: seen.append((done, total, label)))
    assert seen and seen[-1][0] == seen[-1][1] and {label for _, _, label in seen} == {"tc7-1"}
    assert [done for done, _, _ in seen] == sorted(done for done, _, _ in seen)

    class Bar:  # what the module uses of tqdm's
        def __init__(self):
            self.n, self.total, self.description = 0, None, ""

        def reset(self, total):
            self.n, self.total = 0, total

        def set_description(self, text):
            self.description = text

        def update(self, n):
            self.n += n

    bar = Bar()
    figgen.render("tc7-1", scale=0.5, progress=bar)
    assert bar.n == bar.total > 0 and bar.description == "tc7-1"


def test_ctrl_c_stops_a_render_between_steps_and_leaves_no_file(tmp_path):
    # A long run (Gray-Scott on 512 x 512 cells); Ctrl-C is simulated on this thread.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        figgen.render("tc7-2", out=tmp_path, set={"n": 512}, formats=("png", "mp4"))
    assert time.monotonic() - started < 20
    assert list(tmp_path.iterdir()) == []
    # The process renders on afterwards.
    assert figgen.render("tc7-1", scale=0.5).metadata["id"] == "tc7-1"


def test_the_gil_is_released_and_two_threads_take_turns():
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.01)

    ticker = threading.Thread(target=tick)
    ticker.start()
    results = {}

    def render(name, k):  # Gray-Scott on 192 x 192 cells: about a second each
        results[name] = figgen.render("tc7-2", set={"n": 192, "k": k}, scale=0.5)

    threads = [threading.Thread(target=render, args=(f"k{k}", k)) for k in (0.057, 0.06)]
    started = time.monotonic()
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    stop.set()
    ticker.join()
    assert results["k0.057"].metadata["params"]["k"] == pytest.approx(0.057)
    assert results["k0.06"].metadata["params"]["k"] == pytest.approx(0.06)
    # Python ran while both rendered.
    assert sum(1 for t in ticks if t > started) > 5


def sha256(path):
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


def state_hashes(meta):
    """Every "state_sha256" in a figure's metadata, by its place."""
    found = {}

    def walk(node, where):
        if isinstance(node, dict):
            for key, value in node.items():
                if key == "state_sha256":
                    found[where] = value
                else:
                    walk(value, f"{where}/{key}")
        elif isinstance(node, list):
            for i, value in enumerate(node):
                walk(value, f"{where}/{i}")

    walk(meta, "")
    return found


def golden_overrides(figure):
    """The --set lines the figure's golden is rendered with (tests/golden/ID.set): a heavy figure made lighter."""
    lines = (GOLDEN / f"{figure}.set").read_text().splitlines() if (GOLDEN / f"{figure}.set").exists() else []
    return [line.strip() for line in lines if line.strip() and not line.lstrip().startswith("#")]


def same_bits_figures():
    """tests/python/same_bits_figures.txt: figure id -> (the formats compared, --set lines)."""
    cases = {}
    for line in (pathlib.Path(__file__).parent / "same_bits_figures.txt").read_text().splitlines():
        words = line.split("#")[0].split()
        if words:
            cases[words[0]] = (words[1], words[2:])
    return cases


SAME_BITS = same_bits_figures()


def test_each_route_has_a_figure_held_to_the_command():
    catalog = {p.stem for p in FIGURES.glob("*.toml")}
    assert set(SAME_BITS) <= catalog
    assert any("mp4" in formats for formats, _ in SAME_BITS.values())
    assert any((GOLDEN / f"{figure}.set").exists() for figure in SAME_BITS)


@pytest.mark.parametrize("figure", sorted(SAME_BITS))
def test_the_same_bits_as_the_command(figure, tmp_path):
    """A figure at scale 0.5, as its golden is made (and with the list's own --set lines): the PNG's pixels,
    every state hash and the MP4's bytes."""
    by_command, by_python = tmp_path / "command", tmp_path / "python"
    formats, own_sets = SAME_BITS[figure]
    films = "mp4" in formats
    sets = golden_overrides(figure) + own_sets
    run = command("render", figure, "--scale", "0.5", "--format", formats, "--out", str(by_command),
                  *[arg for s in sets for arg in ("--set", s)])
    assert run.returncode == 0, run.stderr
    as_dict = dict(s.split("=", 1) for s in sets)
    fig = figgen.render(figure, scale=0.5, formats=formats.split(","), out=by_python,
                        set={key: tomllib.loads(f"v = {value}")["v"] for key, value in as_dict.items()})
    made = json.loads((by_command / f"{figure}.json").read_text())
    assert fig.metadata["image"] == made["image"]
    assert state_hashes(fig.metadata) == state_hashes(made)
    width, height = made["image"]["size"]
    command_pixels = figgen._figgen.read_png(str(by_command / f"{figure}.png"))
    assert figgen._figgen.read_png(str(fig._path(".png"))) == command_pixels
    if films:
        assert sha256(fig.film) == sha256(by_command / f"{figure}.mp4")


def test_a_bad_argument_names_the_argument():
    cases = [(dict(scale=9), "scale", "a number from 0.1 to 8"),
             (dict(formats=("png", "gif")), "formats", "png, pdf, svg, mp4, webm, frames, vti, vtu"),
             (dict(threads=0), "threads", "an integer from 1 to 1024"),
             (dict(gl="vulkan"), "gl", "auto, osmesa, egl or egl-device")]
    for arguments, key, allowed in cases:
        with pytest.raises(figgen.SettingError) as caught:
            figgen.render("tc7-1", **arguments)
        e = caught.value
        assert (e.key, e.value, e.allowed) == (key, repr(arguments[key]), allowed)
        assert e.where == f"{key}={arguments[key]!r}"
    with pytest.raises(TypeError):
        figgen.render({"params": {"n": object()}})
    deep = []
    for _ in range(100000):  # far deeper than any description, and than the C stack would take
        deep = [deep]
    with pytest.raises(ValueError, match="at most 32 deep"):
        figgen.render({"params": {"n": deep}})


def command_error(*args):
    """The command's one line for a refused render, without its prefix and its "; see figgen --help"."""
    out = [] if "--out" in args else ["--out", os.devnull + "/never"]  # never made: the mistake comes first
    run = subprocess.run([FIGGEN, "render", *args, *out], capture_output=True)
    assert run.returncode == 2 and run.stdout == b""
    line = run.stderr.decode("utf-8").strip()
    assert line.startswith("figgen: error: ") and "\n" not in line, line
    return line[len("figgen: error: "):].removesuffix("; see figgen --help")


# Each mistake as render()'s argument and as figgen render's option, each
# naming it its own way, then the same words: (arguments, options, how
# Python names it, how the command does, what is allowed).
BIG = 2**70
SAME_MISTAKES = [
    (dict(seed=BIG), ["--seed", str(BIG)], f"seed={BIG}", f"--seed: {BIG}",
     "an integer from 0 to 9223372036854775807"),
    (dict(seed=2**64), ["--seed", str(2**64)], f"seed={2**64}", f"--seed: {2**64}",
     "an integer from 0 to 9223372036854775807"),
    (dict(seed=2**63), ["--seed", str(2**63)], f"seed={2**63}", f"--seed: {2**63}",
     "an integer from 0 to 9223372036854775807"),
    (dict(seed=-1), ["--seed", "-1"], "seed=-1", "--seed: -1", "an integer from 0 to 9223372036854775807"),
    (dict(threads=-1), ["--threads", "-1"], "threads=-1", "--threads: -1", "an integer from 1 to 1024"),
    (dict(threads=BIG), ["--threads", str(BIG)], f"threads={BIG}", f"--threads: {BIG}", "an integer from 1 to 1024"),
    (dict(scale=0), ["--scale", "0"], "scale=0", "--scale 0", "a number from 0.1 to 8"),
    (dict(scale=float("nan")), ["--scale", "nan"], "scale=nan", "--scale nan", "a number from 0.1 to 8"),
    (dict(size="5"), ["--size", "5"], "size='5'", "--size 5", "WIDTHxHEIGHT, each 2..16384, e.g. 1200x600"),
    (dict(size=(1, 5)), ["--size", "1x5"], "size=(1, 5)", "--size 1x5", "WIDTHxHEIGHT, each 2..16384, e.g. 1200x600"),
    (dict(gl="foo"), ["--gl", "foo"], "gl='foo'", "--gl foo", "auto, osmesa, egl or egl-device"),
    (dict(formats="xyz"), ["--format", "xyz"], "formats='xyz'", "--format: xyz",
     "png, pdf, svg, mp4, webm, frames, vti, vtu"),
    (dict(formats=["png", "xyz"]), ["--format", "png,xyz"], "formats=['png', 'xyz']: 'xyz'", "--format: xyz",
     "png, pdf, svg, mp4, webm, frames, vti, vtu"),
]


@pytest.mark.parametrize("arguments, options, named, command_named, allowed", SAME_MISTAKES,
                         ids=[c[2] for c in SAME_MISTAKES])
def test_a_bad_argument_is_refused_in_the_commands_words(arguments, options, named, command_named, allowed, tmp_path):
    said = command_error("tc7-1", *options)
    assert said.startswith(command_named + " is not allowed: use " + allowed), said
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", out=tmp_path / "out", **arguments)
    e = caught.value
    (key, given), = arguments.items()
    assert str(e) == named + said[len(command_named):]
    assert (e.key, e.value, e.allowed, e.where) == (key, repr(given), allowed, f"{key}={given!r}")
    assert not (tmp_path / "out").exists()  # refused before anything was made


def test_an_out_folder_figgen_cannot_make_is_refused_in_the_commands_words():
    said = command_error("tc7-1", "--out", "/proc/figgen")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", out="/proc/figgen")
    e = caught.value
    assert said.startswith("--out /proc/figgen: cannot create the folder /proc/figgen")
    assert str(e) == "out='/proc/figgen'" + said[len("--out /proc/figgen"):]
    assert said.endswith("; allowed: a folder figgen can write")
    assert (e.key, e.value, e.allowed, e.where) == ("out", "'/proc/figgen'", "a folder figgen can write",
                                                  "out='/proc/figgen'")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", out="")
    assert str(caught.value) == "out='' is empty: give the folder the figures go into, e.g. --out out"


WRONG_KINDS = [
    (dict(seed=1.5), "seed=1.5 is not allowed: use an integer or None, not float"),
    (dict(seed="7"), "seed='7' is not allowed: use an integer or None, not str"),
    (dict(seed=True), "seed=True is not allowed: use an integer or None, not bool"),
    (dict(threads=2.0), "threads=2.0 is not allowed: use an integer or None, not float"),
    (dict(formats=[1, 2]), 'formats=[1, 2] is not allowed: use format names ("png", or ["png", "mp4"]), not int'),
    (dict(formats=5), 'formats=5 is not allowed: use format names ("png", or ["png", "mp4"]), not int'),
    (dict(size=5), 'size=5 is not allowed: use (width, height) or "WxH", not int'),
    (dict(size=(1.5, 2)), 'size=(1.5, 2) is not allowed: use (width, height) or "WxH" with integers, not float'),
    (dict(scale="big"), "scale='big' is not allowed: use a number, not str"),
    (dict(gl=5), 'gl=5 is not allowed: use "auto", "osmesa", "egl" or "egl-device", not int'),
    (dict(out=5), "out=5 is not allowed: use a folder's path or None, not int"),
    (dict(progress=5), "progress=5 is not allowed: use a callable(done, total, label) or a tqdm bar, not int"),
    (dict(set=[("r", 1)]),
     "set=[('r', 1)] is not allowed: use a dict {key: value} ({\"r\": 0.2, \"style.alpha\": 0.5}), not list"),
    (dict(set={5: 1}), "set={5: 1} is not allowed: use a dict whose keys are text (\"r\", \"style.alpha\"), not int"),
    (dict(set={"r": None}), "r: a description holds booleans, numbers, strings, lists and dicts, not NoneType"),
]


@pytest.mark.parametrize("arguments, message", WRONG_KINDS, ids=[m.split(" ")[0] for _, m in WRONG_KINDS])
def test_an_argument_of_the_wrong_kind_is_a_type_error_naming_it(arguments, message, tmp_path):
    with pytest.raises(TypeError) as caught:
        figgen.render("tc7-1", **{"out": tmp_path / "out", **arguments})
    assert str(caught.value) == message
    assert not (tmp_path / "out").exists()


def test_a_figure_of_the_wrong_kind_is_a_type_error():
    with pytest.raises(TypeError) as caught:
        figgen.render(5)
    assert str(caught.value) == ("figure=5 is not allowed: use a catalog id, a path to a description, its TOML text "
                                 "or a dict, not int")
    with pytest.raises(TypeError) as caught:
        figgen.render({"scene": "diffusion", 5: 1})
    assert str(caught.value) == "a description's keys are text, not int"


def test_text_python_cannot_encode_is_refused_as_the_command_refuses_its_bytes():
    """A lone surrogate has no UTF-8: as the bytes Python writes for it (ED A0 80), what the command says of them."""
    said = command_error(b"\xed\xa0\x80")
    assert said.startswith("unknown figure id '\\xED\\xA0\\x80'; closest: ")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("\ud800")
    assert str(caught.value) == said and caught.value.key is None
    with pytest.raises(figgen.SettingError) as caught:
        figgen.describe("\ud800")
    assert str(caught.value) == said
    # A key: the command's words for --set with those bytes.
    said = command_error("tc7-1", "--set", b"\xed\xa0\x80=1")
    assert said.startswith("--set \\xED\\xA0\\x80=1: unknown key params.\\xED\\xA0\\x80; allowed: n, r, ")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", set={"\ud800": 1})
    assert str(caught.value) == said and caught.value.key == "params.\\xED\\xA0\\x80"
    # A value: refused as the reader refuses a string that is not UTF-8 text.
    text_allowed = ("text of valid UTF-8 characters, without control characters other than tab and line breaks and "
                    "without noncharacters (U+FDD0..U+FDEF, U+FFFE and U+FFFF of each plane)")
    said = command_error("tc7-1", "--set", b'style.sampling="\xed\xa0\x80"')
    assert said.startswith("--set style.sampling=") and "\\xED\\xA0\\x80" in said
    assert said.endswith(" is not allowed: " + text_allowed)
    for key in ("r", "style.sampling"):
        with pytest.raises(figgen.SettingError) as caught:
            figgen.render("tc7-1", set={key: "\ud800"})
        e = caught.value
        assert str(e) == f'{key} = "\\xED\\xA0\\x80" is not allowed: {text_allowed}'
        assert (e.key, e.value, e.allowed, e.where) == (key, '"\\xED\\xA0\\x80"', text_allowed, f"set={key}='\\ud800'")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render({"id": "\ud800", "scene": "diffusion"})
    assert (caught.value.key, caught.value.where) == ("id", "<dict>")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("\ud800\n")  # a description's text
    assert "pybind11" not in str(caught.value) and "Unable to cast" not in str(caught.value)


def test_an_integer_toml_cannot_hold_is_refused_as_the_command_refuses_it():
    said = command_error("tc7-1", "--set", f"n={BIG}")
    assert said.startswith(f"--set n={BIG}: n = ") and said.endswith(" is not allowed: expected an integer")
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", set={"n": BIG})
    assert str(caught.value) == said
    assert (caught.value.key, caught.value.where) == ("params.n", f"set=n={BIG}")
    # Inside a list or a dict, where TOML has no text for it: the key and the integers allowed.
    int64 = "an integer from -9223372036854775808 to 9223372036854775807"
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render("tc7-1", set={"figure.panels": [0, BIG]})
    e = caught.value
    assert str(e) == f"figure.panels[1] = {BIG} is not allowed: {int64}"
    assert (e.key, e.value, e.allowed) == ("figure.panels[1]", str(BIG), int64)
    assert e.where == f"set=figure.panels=[0, {BIG}]"
    with pytest.raises(figgen.SettingError) as caught:
        figgen.render({"scene": "diffusion", "params": {"n": -BIG}})
    assert (caught.value.key, caught.value.value, caught.value.where) == ("params.n", str(-BIG), "<dict>")


def test_numpy_integers_are_integers():
    numpy = pytest.importorskip("numpy")
    fig = figgen.render("tc7-1", scale=0.5, seed=numpy.int64(3), set={"n": numpy.int32(12)},
                        size=(numpy.int64(400), 200))
    assert (fig.metadata["seed"], fig.metadata["params"]["n"]) == (3, 12)


def test_a_folder_whose_name_is_not_utf8(tmp_path):
    folder = tmp_path / "caf\udce9"  # the byte E9, as Python names it (surrogateescape)
    fig = figgen.render("tc7-1", scale=0.5, out=folder)
    assert os.fsencode(fig.paths[0]) == os.fsencode(tmp_path) + b"/caf\xe9/tc7-1.png"
    assert fig.metadata["id"] == "tc7-1"
    numpy = pytest.importorskip("numpy")
    assert fig.pixels.shape[2] == 4 and fig.pixels.dtype == numpy.uint8


VTI = pathlib.Path(__file__).parent.parent / "ready" / "vti"


def test_a_damaged_pattern_is_a_file_error_with_the_commands_words(tmp_path):
    # Issue 46: zlib block sizes 2**63 and 2**63 + L, which wrap to L, once
    # read 2**63 bytes past the data and killed the interpreter.
    text = bytearray((VTI / "appended-raw-zlib-f32.vti").read_bytes())
    at = text.index(b"_", text.index(b"<AppendedData")) + 1
    words = [int.from_bytes(text[at + 8 * i:at + 8 * i + 8], "little") for i in range(6)]
    assert words[0] == 3
    words[3], words[4] = 2**63, (2**63 + words[3] + words[4]) % 2**64
    text[at:at + 48] = b"".join(w.to_bytes(8, "little") for w in words)
    damaged = tmp_path / "wrap.vti"
    damaged.write_bytes(bytes(text))
    with pytest.raises(figgen.FileError) as raised:
        figgen.render(damaged, out=tmp_path / "out")
    said = command("render", str(damaged), "--out", str(tmp_path / "out"))
    assert said.returncode == 2
    assert str(raised.value) == said.stderr.strip().removeprefix("figgen: error: ")
    assert "a compressed block's size is 9223372036854775808 bytes" in str(raised.value)
    assert isinstance(raised.value, figgen.SettingError) and raised.value.key is None
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
    mesh = tmp_path / "bunny.vtu"
    mesh.write_text("<VTKFile type='UnstructuredGrid'/>")
    with pytest.raises(figgen.FileError, match="no <RD> in <VTKFile>"):
        figgen.describe(mesh)


def test_describe_reads_a_pattern_file():
    d = figgen.describe(VTI / "binary-zlib-f64.vti")
    assert d["id"] == "binary-zlib-f64"
    assert d["scene"] == "formula"
    params = {k["key"]: k["value"] for k in d["settings"]["params"]}
    assert params["D"] == 0.5
    assert params["data_type"] == "double"


def test_a_formula_model_strict_and_its_error_measured(tmp_path):
    # fx-tc7-2's Gray-Scott (its own 9-point kernel, ra = 0.5): a timestep of 5 is past its explicit bound.
    short = {"steps": 100, "figure.panels": [100], "animation.steps": [0, 100]}
    with pytest.raises(figgen.SettingError) as refused:
        figgen.render("fx-tc7-2", out=tmp_path, set={**short, "timestep": 5.0}, strict=True)
    assert refused.value.key == "params.timestep" and "explicit stability bound" in str(refused.value)
    assert list(tmp_path.iterdir()) == []
    # In double, 100 steps: Euler's error in time halves with the timestep.
    fig = figgen.render("fx-tc7-2", out=tmp_path, formats="png", error=True, set=short)
    orders = [c["order"] for c in fig.metadata["error"]["chemicals"]]
    assert orders == [pytest.approx(1, abs=0.1), pytest.approx(1, abs=0.1)]
    with pytest.raises(TypeError):
        figgen.render("fx-tc7-2", out=tmp_path, error="yes")
