"""figgen from Python: render, describe and show figures and films.

    import figgen
    fig = figgen.render("tc7-2", set={"f": 0.04}, scale=0.5)
    fig            # in Jupyter: the figure itself

A render runs in this process, through the same library as the `figgen`
command, with the same bits for the same description, options and seed.
Renders share one GL context and the modules they load; one runs at a time
(a second thread's render waits for the first). The GIL is released while
a figure renders, and Ctrl-C stops it between two steps, leaving no file.
"""

import base64
import collections.abc
import html
import json
import math
import numbers
import operator
import os
import pathlib
import shutil
import tempfile
import weakref

from . import _figgen

__all__ = ["catalog", "describe", "render", "Figure", "SettingError", "FileError", "RenderError"]


class SettingError(ValueError):
    """A setting figgen does not allow.

    key: the key as the description names it ("params.r", "style.sides"),
    None where the mistake names none (an unknown figure id); value: as
    given; allowed: what is; where: the file and line, or the Python
    argument, that gave it.
    """

    def __init__(self, message, key="", value="", allowed="", where=""):
        super().__init__(message)
        self.key = key or None
        self.value = value
        self.allowed = allowed
        self.where = where


class FileError(SettingError):
    """A file given as the figure that figgen cannot read as one: a Ready
    pattern (.vti) that is damaged, not a pattern, or of a kind figgen does
    not run yet (a mesh, .vtu). Its message is the command's one line, which
    names the file and what is wrong; key is None.
    """

    def __init__(self, message):
        super().__init__(message)


class RenderError(RuntimeError):
    """A render that failed while it ran or wrote: figgen's one-line message."""


class _OptionError(Exception):
    """_figgen's word for a refused option ("--scale"): render() raises it as
    a SettingError naming its own argument, with the value as given."""

    def __init__(self, option, value, allowed, rest):
        super().__init__(option, value, allowed, rest)
        self.option, self.value, self.allowed, self.rest = option, value, allowed, rest


def catalog():
    """The catalog's figures: {id: title}, in `figgen list`'s order."""
    return {figure_id: title for figure_id, title, _ in _figgen.catalog()}


def _text(text):
    """A str as figgen's C++ takes it: UTF-8 bytes, a surrogate as the bytes
    Python writes for it (os.fsencode's, else surrogatepass), which figgen
    refuses in the command's words instead of pybind11's."""
    try:
        return text.encode("utf-8", "surrogateescape")
    except UnicodeEncodeError:
        return text.encode("utf-8", "surrogatepass")


def _shown(value):
    """repr(value) for a one-line message: a long one cut, as the command cuts a long value."""
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _kind(name, value, allowed, wrong=None):
    """TypeError for an argument of the wrong kind (`wrong`: the part of `value` that is)."""
    wrong = value if wrong is None else wrong
    return TypeError(f"{name}={_shown(value)} is not allowed: use {allowed}, not {type(wrong).__name__}")


def _target(figure):
    """(target, text): a catalog id or a file, or a description's TOML text."""
    if isinstance(figure, dict):
        try:
            return "<dict>", _figgen.toml_text(figure)
        except SettingError as e:
            e.where = "<dict>"
            raise
    if isinstance(figure, os.PathLike):
        path = os.fspath(figure)
        return (path if isinstance(path, bytes) else _text(path)), None
    if not isinstance(figure, str):
        raise _kind("figure", figure, "a catalog id, a path to a description, its TOML text or a dict")
    if "\n" in figure or ("=" in figure and not os.path.exists(figure)):
        return "<string>", _text(figure)
    return _text(figure), None


def describe(figure):
    """Every setting of a figure, as Python data.

    Returns {"id", "title", "source", "scene", "seed", "file", "settings"},
    where settings maps each section ("params", "style", "params.plants[0]",
    "figure", "animation") to its keys, each {"key", "value", "default",
    "allowed", "meaning"} (value and default None where there is none).
    """
    target, text = _target(figure)
    d = _figgen.describe(target, text)
    d["settings"] = {name: keys for name, keys in d.pop("sections")}
    return d


_INT64 = (-2**63, 2**63 - 1)


def _assignments(settings):
    """set={...} as figgen's --set assignments, TOML values."""
    if settings is None:
        return []
    if not isinstance(settings, collections.abc.Mapping):
        raise _kind("set", settings, 'a dict {key: value} ({"r": 0.2, "style.alpha": 0.5})')
    out = []
    for key, value in settings.items():
        if not isinstance(key, str):
            raise _kind("set", settings, 'a dict whose keys are text ("r", "style.alpha")', key)
        if isinstance(value, int) and not isinstance(value, bool) and not _INT64[0] <= value <= _INT64[1]:
            text = str(value).encode()  # no TOML integer: the description's reader refuses it in the command's words
        else:
            try:
                text = _figgen.toml_value(value, _text(key))
            except SettingError as e:
                e.where = f"set={key}={_shown(value)}"
                raise
        out.append(_text(key) + b"=" + text)
    return out


# figgen render's options as render()'s arguments name them.
_ARGUMENTS = {"--scale": "scale", "--format": "formats", "--size": "size", "--threads": "threads", "--gl": "gl",
              "--out": "out", "--seed": "seed"}


def _argument_error(error, given):
    """A refused option as a SettingError naming render()'s argument, with its value as given."""
    name = _ARGUMENTS[error.option]
    where = f"{name}={_shown(given[name])}"
    named = where
    if name == "formats" and not isinstance(given[name], str):  # the name refused, of those given
        allowed = error.allowed.split(", ")
        named += ": " + _shown(next((f for f in given[name] if f not in allowed), error.value))
    return SettingError(named + error.rest, name, repr(given[name]), error.allowed, where)


def _integer(name, value, allowed):
    """An integer argument (int, or anything with __index__ but bool) as decimal text, or None."""
    if value is None:
        return None
    if isinstance(value, bool) or not hasattr(type(value), "__index__"):
        raise _kind(name, value, allowed)
    return str(operator.index(value))


_FORMATS_KIND = 'format names ("png", or ["png", "mp4"])'


def _formats(formats):
    if isinstance(formats, str):
        return [_text(formats)]
    if not isinstance(formats, (list, tuple)):  # an ordered list: the files are written in the table's order anyway
        raise _kind("formats", formats, _FORMATS_KIND)
    for f in formats:
        if not isinstance(f, str):
            raise _kind("formats", formats, _FORMATS_KIND, f)
    return [_text(f) for f in formats]


_SIZE_KIND = '(width, height) or "WxH"'


def _size(size):
    """size as --size's text: (width, height) or "WxH"."""
    if size is None:
        return b""
    if isinstance(size, str):
        return _text(size)
    if isinstance(size, (tuple, list)) and len(size) == 2:
        for n in size:
            if isinstance(n, bool) or not hasattr(type(n), "__index__"):
                raise _kind("size", size, _SIZE_KIND + " with integers", n)
        return f"{operator.index(size[0])}x{operator.index(size[1])}".encode()
    raise _kind("size", size, _SIZE_KIND)


def _scale(scale):
    if isinstance(scale, bool) or not isinstance(scale, numbers.Real):
        raise _kind("scale", scale, "a number")
    try:
        return float(scale)
    except OverflowError:  # an int past any float: out of range, and refused as such
        return math.inf


def _progress_callback(progress):
    """A callable(done, total, label) from a callable or a tqdm bar."""
    if progress is None or callable(progress) and not hasattr(progress, "update"):
        return progress
    if not all(hasattr(progress, a) for a in ("update", "reset", "set_description", "n", "total")):
        raise _kind("progress", progress, "a callable(done, total, label) or a tqdm bar")
    bar = progress  # tqdm: total, n, set_description, update

    def report(done, total, label):
        if bar.total != total:
            bar.reset(total=total)
            bar.set_description(label)
        bar.update(done - bar.n)

    return report


def render(figure, *, out=None, set=None, seed=None, formats=("png",), size=None, scale=1.0, gl="auto",
           threads=None, progress=None, strict=False, error=False):
    """Renders a figure in this process and returns its Figure.

    figure: a catalog id ("tc7-1"), a path to a description or a Ready
    pattern (.vti), a description's TOML text, or a dict with a
    description's keys. set: {key: value} as --set ("r", "style.alpha");
    formats: --format's names ("png", "pdf", "svg", "mp4", "webm", "frames",
    "vti"); size: (width, height) or "WxH"; out: the folder the files go
    into (None: a temporary folder the Figure owns, removed with it).
    progress: a callable(done, total, label) or a tqdm bar. strict: refuse a
    formula model's timestep past its stability bound (--strict); error:
    measure a formula model's error in time (--error).

    Every argument is checked before anything runs: TypeError for one of
    the wrong kind, SettingError for a value figgen does not allow (in the
    command's words). Raises RenderError for a failure while running or
    writing, KeyboardInterrupt on Ctrl-C, and what the progress callback
    raises, as it raised it.
    """
    given = {"scale": scale, "formats": formats, "size": size, "threads": threads, "gl": gl, "out": out,
             "seed": seed}
    # Every kind checked before anything is made (a temporary folder, a render).
    target, text = _target(figure)
    arguments = (_assignments(set), _integer("seed", seed, "an integer or None"), _formats(formats), _size(size),
                 _scale(scale))
    if not isinstance(gl, str):
        raise _kind("gl", gl, '"auto", "osmesa", "egl" or "egl-device"')
    count = _integer("threads", threads, "an integer or None")
    for name, flag in (("strict", strict), ("error", error)):
        if not isinstance(flag, bool):
            raise _kind(name, flag, "True or False")
    if out is not None and not isinstance(out, (str, bytes, os.PathLike)):
        raise _kind("out", out, "a folder's path or None")
    report = _progress_callback(progress)
    owned = out is None
    folder = tempfile.mkdtemp(prefix="figgen-") if owned else os.fspath(out)
    try:
        try:
            done = _figgen.render(target, text, *arguments, _text(gl), count,
                                  folder if isinstance(folder, bytes) else _text(folder), strict, error, report)
        except _OptionError as e:
            raise _argument_error(e, given) from None
        except SettingError as e:
            if e.where.startswith("--set "):
                e.where = "set=" + e.where[len("--set "):]
            raise
    except BaseException:
        if owned:
            shutil.rmtree(folder, ignore_errors=True)
        raise
    return Figure(done["id"], pathlib.Path(done["json"]), [pathlib.Path(f) for f in done["files"]],
                  folder if owned else None)


class Figure:
    """A rendered figure: its files, its metadata, its image.

    metadata: the figure's JSON as a dict; png: the PNG's bytes; pixels: a
    NumPy array, height x width x 4, uint8 (NumPy needed); paths: every
    file written; film: the MP4's path, or None. In Jupyter it shows itself,
    with its film as a <video> when it has one.
    """

    def __init__(self, figure_id, json_path, paths, owned_folder=None):
        self.id = figure_id
        self.paths = paths
        self._json_path = json_path
        self._metadata = None
        if owned_folder is not None:
            self._cleanup = weakref.finalize(self, shutil.rmtree, owned_folder, True)

    @property
    def metadata(self):
        if self._metadata is None:
            self._metadata = json.loads(self._json_path.read_text(encoding="utf-8"))
        return self._metadata

    def _path(self, suffix):
        for p in self.paths:
            if p.name == self.id + suffix:
                return p
        return None

    @property
    def png(self):
        return self._path(".png").read_bytes()

    @property
    def pixels(self):
        import numpy  # only for this

        width, height, rgba = _figgen.read_png(os.fsencode(self._path(".png")))  # any folder's name, as bytes
        return numpy.frombuffer(rgba, dtype=numpy.uint8).reshape(height, width, 4)

    @property
    def film(self):
        return self._path(".mp4")

    def _repr_png_(self):
        return self.png

    def _repr_html_(self):
        if self.film is None:
            return None
        video = base64.b64encode(self.film.read_bytes()).decode("ascii")
        title = html.escape(self.metadata.get("title", self.id))
        return (f'<figure><video controls loop autoplay muted playsinline title="{title}" '
                f'src="data:video/mp4;base64,{video}"></video><figcaption>{title}</figcaption></figure>')

    def __repr__(self):
        return f"<figgen.Figure {self.id}: {', '.join(p.name for p in self.paths)}>"
