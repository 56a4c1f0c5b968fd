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
import html
import json
import os
import pathlib
import shutil
import tempfile
import weakref

from . import _figgen

__all__ = ["catalog", "describe", "render", "Figure", "SettingError", "RenderError"]


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


class RenderError(RuntimeError):
    """A render that failed while it ran or wrote: figgen's one-line message."""


def catalog():
    """The catalog's figures: {id: title}, in `figgen list`'s order."""
    return {figure_id: title for figure_id, title, _ in _figgen.catalog()}


def _target(figure):
    """(target, text): a catalog id or a file, or a description's TOML text."""
    if isinstance(figure, dict):
        return "<dict>", _figgen.toml_text(figure)
    if isinstance(figure, os.PathLike):
        return os.fspath(figure), None
    if not isinstance(figure, str):
        raise TypeError("figure: a catalog id, a path to a description, its TOML text or a dict, not "
                        + type(figure).__name__)
    if "\n" in figure or ("=" in figure and not os.path.exists(figure)):
        return "<string>", figure
    return figure, None


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


def _assignments(settings):
    """set={...} as figgen's --set assignments, TOML values."""
    out = []
    for key, value in (settings or {}).items():
        out.append(f"{key}={_figgen.toml_value(value)}")
    return out


# figgen's options as render()'s arguments name them.
_ARGUMENTS = {"--scale": "scale", "--format": "formats", "--size": "size", "--threads": "threads", "gl": "gl",
              "--out": "out", "--seed": "seed"}


def _name_argument(error, given):
    """Says which argument of render() gave what the error refuses."""
    if error.where.startswith("--set "):
        error.where = "set=" + error.where[len("--set "):]
        return
    if error.key is not None:
        return
    option = str(error).split(" ", 1)[0].split("=", 1)[0].rstrip(":")
    name = _ARGUMENTS.get(option)
    if name is not None:
        error.key = name
        error.where = f"{name}={given[name]!r}"


def _progress_callback(progress):
    """A callable(done, total, label) from a callable or a tqdm bar."""
    if progress is None or callable(progress) and not hasattr(progress, "update"):
        return progress
    bar = progress  # tqdm: total, n, set_description, update

    def report(done, total, label):
        if bar.total != total:
            bar.reset(total=total)
            bar.set_description(label)
        bar.update(done - bar.n)

    return report


def render(figure, *, out=None, set=None, seed=None, formats=("png",), size=None, scale=1.0, gl="auto",
           threads=None, progress=None):
    """Renders a figure in this process and returns its Figure.

    figure: a catalog id ("tc7-1"), a path to a description or a Ready
    pattern (.vti), a description's TOML text, or a dict with a
    description's keys. set: {key: value} as --set ("r", "style.alpha");
    formats: --format's names ("png", "pdf", "svg", "mp4", "webm", "frames",
    "vti"); size: (width, height) or "WxH"; out: the folder the files go
    into (None: a temporary folder the Figure owns, removed with it).
    progress: a callable(done, total, label) or a tqdm bar.

    Raises SettingError for a setting figgen does not allow, RenderError
    for a failure while running or writing, KeyboardInterrupt on Ctrl-C.
    """
    target, text = _target(figure)
    if isinstance(size, (tuple, list)):
        size = f"{size[0]}x{size[1]}"
    if isinstance(formats, str):
        formats = (formats,)
    owned = out is None
    folder = tempfile.mkdtemp(prefix="figgen-") if owned else os.fspath(out)
    try:
        try:
            done = _figgen.render(target, text, _assignments(set), seed, list(formats), size or "", float(scale), gl,
                                  threads, folder, _progress_callback(progress))
        except SettingError as e:
            _name_argument(e, {"scale": scale, "formats": formats, "size": size, "threads": threads, "gl": gl,
                               "out": out, "seed": seed})
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

        width, height, rgba = _figgen.read_png(str(self._path(".png")))
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
