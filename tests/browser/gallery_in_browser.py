#!/usr/bin/python3
"""The gallery checked in a real browser: Debian's headless Chromium, driven
through chromedriver (python3-selenium), over a gallery served on a loopback
port.

    gallery_in_browser.py --figgen build/figgen --out DIR --screenshot FILE.png
    gallery_in_browser.py --gallery out --screenshot FILE.png

The first renders a few figures into DIR (some with a film, some without) and
writes their gallery; the second takes a gallery already written (`make
figures` writes out/index.html; `make gallery-check` checks it) with every
figure whose ID.json is in the folder. Either way it serves the folder on
127.0.0.1 and checks in the browser that every image has loaded (natural
size > 0, the size in its tag), every video has loaded its metadata
(duration > 0, the frame count over the fps of its metadata, its size),
has its poster (the frame its description names, else its last, at its
size) and seeks to its last frame, every film's card shows the film's
animated preview (ID.webp, at its metadata's size, looping) in the film's
place until the film is opened to play, and then the film with its poster,
nothing was logged to the console, and a phone-wide
window with every card's details open needs no sideways scrolling; then
that each figure's SVG (the --figgen run writes them) opens on its own as
an SVG document of the figure's size, with nothing in the console. Saves a
whole-page desktop screenshot and a phone one. Exits 0 when all holds, 1 with
one line per failure otherwise.
"""
import argparse
import functools
import http.server
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service

FIGURES = ["tc7-1", "tc7-9", "sf87-3", "pl-ifs-fern"]


class QuietHandler(http.server.SimpleHTTPRequestHandler):
    """The standard library's file server plus single byte ranges
    ("Range: bytes=A-B"), which browsers need to seek in a video, as any
    real web server and file:// give them."""

    def log_message(self, *args):
        pass

    def send_head(self):
        # A document without a <link rel="icon"> of its own (an SVG opened
        # directly) makes the browser ask for /favicon.ico: answered with no
        # content, as a site without one would, not a 404 in the console.
        if self.path == "/favicon.ico":
            self.send_response(204)
            self.end_headers()
            return None
        match = re.fullmatch(r"bytes=(\d*)-(\d*)", self.headers.get("Range", ""))
        path = self.translate_path(self.path)
        if not match or not os.path.isfile(path) or match.group(1) == match.group(2) == "":
            return super().send_head()
        size = os.path.getsize(path)
        first, last = match.groups()
        if first == "":  # the last N bytes
            first, last = max(0, size - int(last)), size - 1
        else:
            first, last = int(first), min(int(last), size - 1) if last else size - 1
        if first >= size or first > last:
            self.send_response(416)
            self.send_header("Content-Range", "bytes */%d" % size)
            self.end_headers()
            return None
        with open(path, "rb") as f:
            f.seek(first)
            body = f.read(last - first + 1)
        self.send_response(206)
        self.send_header("Content-Type", self.guess_type(path))
        self.send_header("Accept-Ranges", "bytes")
        self.send_header("Content-Range", "bytes %d-%d/%d" % (first, last, size))
        self.send_header("Content-Length", str(last - first + 1))
        self.end_headers()
        return io.BytesIO(body)


class LoopbackServer(http.server.ThreadingHTTPServer):
    def handle_error(self, request, client_address):
        # The browser drops a video's connection once it has the part it
        # wants; that is how media loading works, not a failure.
        if not isinstance(sys.exc_info()[1], (ConnectionResetError, BrokenPipeError)):
            super().handle_error(request, client_address)


def figures_in(folder):
    """The figures a gallery shows: those whose metadata (ID.json) is there."""
    return sorted(f[:-5] for f in os.listdir(folder) if f.endswith(".json"))


def render(figgen, out):
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    subprocess.run([figgen, "render", *FIGURES, "--scale", "0.5", "--format", "png,pdf,svg,mp4", "--out", out],
                   check=True)
    subprocess.run([figgen, "gallery", "--out", out], check=True, stdout=subprocess.DEVNULL)


def browser(profile):
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync",
                 "--disable-dev-shm-usage", "--autoplay-policy=no-user-gesture-required",
                 "--user-data-dir=" + profile, "--window-size=1280,2400"]:
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def wait_for(driver, script, seconds=30):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if driver.execute_script(script):
            return True
        time.sleep(0.05)
    return False


# What shows in each film's place before and after it is opened: for every
# <video>, its card's preview image (src, loaded, natural size, whether it
# is animated, shown) and whether the video is shown.
FILM_PLACES = """
return [...document.querySelectorAll('video')].map(v => {
  const card = v.closest('article'), preview = card.querySelector('img.preview');
  // Rendered for the visitor: laid out, and not inside a closed <details>
  // (whose content Chromium skips as content-visibility: hidden).
  const shown = e => !!e && e.getBoundingClientRect().width > 0 && e.getBoundingClientRect().height > 0
                     && (!e.checkVisibility || e.checkVisibility({checkVisibilityCSS: true}))
                     && !e.closest('details:not([open]) > :not(summary)');
  return [v.getAttribute('src'), preview ? preview.getAttribute('src') : null,
          preview ? preview.complete : false, preview ? preview.naturalWidth : 0,
          preview ? preview.naturalHeight : 0, shown(preview), shown(v),
          v.closest('details.film') !== null];
});"""


def film_previews(driver, films):
    """Failures of the films' previews on the page, as a visitor sees them
    and after opening each film; leaves every film closed again."""
    failures = []
    wait_for(driver, "return [...document.querySelectorAll('img.preview')].every(i => i.complete)", seconds=10)
    before = driver.execute_script(FILM_PLACES)
    if len(before) != len(films):
        failures.append("%d films on the page, expected %d" % (len(before), len(films)))
    for src, preview, complete, width, height, preview_shown, video_shown, in_details in before:
        film = films.get(src)
        if film is None:
            continue
        expected = film.get("preview", {})
        if preview is None:
            failures.append("video %s: its card shows no animated preview" % src)
        elif preview != expected.get("file"):
            failures.append("video %s: its card's preview is %s, its metadata names %s" % (src, preview,
                                                                                         expected.get("file")))
        elif not complete or width <= 0:
            failures.append("video %s: its preview %s did not load" % (src, preview))
        elif [width, height] != expected.get("size"):
            failures.append("video %s: its preview %s is %dx%d, its metadata says %s" % (src, preview, width, height,
                                                                                       expected.get("size")))
        elif not preview_shown or video_shown or not in_details:
            failures.append("video %s: before it is played its card should show the preview %s, not the film "
                            "(preview shown: %s, film shown: %s)" % (src, preview, preview_shown, video_shown))
    # The preview is an animation (more than one frame) as figgen wrote it:
    # its frames in the metadata, and what the browser decodes (ImageDecoder
    # where the browser has it) agree.
    driver.set_script_timeout(30)
    counts = driver.execute_async_script(
        "const done = arguments[arguments.length - 1];"
        "if (typeof ImageDecoder === 'undefined') { done(null); return; }"
        "Promise.all([...document.querySelectorAll('img.preview')].map(i => fetch(i.src).then(r => r.arrayBuffer())"
        ".then(data => { const d = new ImageDecoder({data, type: 'image/webp'});"
        " return Promise.all([d.tracks.ready, d.completed]).then(() => [i.getAttribute('src'),"
        " d.tracks.selectedTrack.frameCount, d.tracks.selectedTrack.animated]); })"
        ".catch(e => [i.getAttribute('src'), -1, String(e)])))"
        ".then(done);")
    by_file = {film.get("preview", {}).get("file"): film for film in films.values()}
    for preview, frames, animated in counts or []:
        film = by_file.get(preview)
        if film is None:
            failures.append("preview %s is not the preview of any film's metadata" % preview)
        elif frames != film["preview"]["frames"] or animated is not True:
            failures.append("preview %s: the browser decodes %s frames (animated: %s), its metadata says %d"
                            % (preview, frames, animated, film["preview"]["frames"]))
    # Opened to play: the film is shown, the preview is not.
    driver.execute_script("document.querySelectorAll('details.film').forEach(d => d.open = true);")
    for src, preview, _, _, _, preview_shown, video_shown, _ in driver.execute_script(FILM_PLACES):
        if src in films and (preview_shown or not video_shown):
            failures.append("video %s: opened to play, its card should show the film, not the preview %s "
                            "(preview shown: %s, film shown: %s)" % (src, preview, preview_shown, video_shown))
    driver.execute_script("document.querySelectorAll('details.film').forEach(d => d.open = false);")
    return failures


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--figgen", help="render a few figures with this figgen, then check their gallery")
    parser.add_argument("--out", help="the folder to render into (with --figgen)")
    parser.add_argument("--gallery", help="check the gallery already written in this folder")
    parser.add_argument("--screenshot", required=True)
    args = parser.parse_args()
    if args.gallery:
        args.out = args.gallery
        if not os.path.isfile(os.path.join(args.out, "index.html")):
            print("gallery_in_browser: error: --gallery %s has no index.html: run `make figures` first" % args.out)
            return 2
        figures = figures_in(args.out)
    elif args.figgen and args.out:
        render(args.figgen, args.out)
        figures = FIGURES
    else:
        parser.error("give --figgen and --out, or --gallery")

    # The films the metadata promises, by file name: {file: animation}.
    films = {}
    for figure in figures:
        with open(os.path.join(args.out, figure + ".json")) as f:
            film = json.load(f).get("animation", {})
        if "file" in film:
            films[film["file"]] = film

    server = LoopbackServer(
        ("127.0.0.1", 0), functools.partial(QuietHandler, directory=args.out))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = "http://127.0.0.1:%d/index.html" % server.server_address[1]

    failures = []
    profile = tempfile.mkdtemp(prefix="figgen-chromium-")
    driver = browser(profile)
    try:
        driver.get(url)
        wait_for(driver, "return document.readyState === 'complete'")
        # Every image decoded (thumbnails and the films' previews); its
        # natural size is the one its tag gives.
        images = driver.execute_script(
            "return [...document.images].map(i => [i.getAttribute('src'), i.complete, i.naturalWidth,"
            " i.naturalHeight, +i.getAttribute('width'), +i.getAttribute('height')]);")
        thumbnails = [i for i in images if i[0].startswith("thumbs/")]
        if len(thumbnails) != len(figures):
            failures.append("%d thumbnails on the page, expected %d" % (len(thumbnails), len(figures)))
        for src, complete, width, height, tag_width, tag_height in images:
            if not complete or width <= 0:
                failures.append("image %s did not load" % src)
            elif (width, height) != (tag_width, tag_height):
                failures.append("image %s is %dx%d, its tag says %dx%d" % (src, width, height, tag_width, tag_height))
        # Every video's metadata loaded: duration, size, against figgen's JSON.
        if not wait_for(driver, "return [...document.querySelectorAll('video')].every(v => v.readyState >= 1"
                                " || v.error)"):
            failures.append("the videos' metadata did not load within 30 s")
        videos = driver.execute_script(
            "return [...document.querySelectorAll('video')].map(v => [v.getAttribute('src'), v.duration,"
            " v.videoWidth, v.videoHeight, v.error ? v.error.code : 0]);")
        if len(videos) != len(films):
            failures.append("%d videos on the page, expected %d" % (len(videos), len(films)))
        for src, duration, width, height, error in videos:
            film = films.get(src)
            if film is None:
                failures.append("video %s is not the film of any figure's metadata" % src)
                continue
            if error:
                failures.append("video %s: media error %d" % (src, error))
                continue
            expected = film["frames"] / film["fps"]
            if not duration or duration <= 0 or abs(duration - expected) > 1.5 / film["fps"]:
                failures.append("video %s lasts %s s, its metadata says %d frames at %d fps (%.3f s)"
                                % (src, duration, film["frames"], film["fps"], expected))
            if [width, height] != film["size"]:
                failures.append("video %s is %dx%d, its metadata says %s" % (src, width, height, film["size"]))
        # Every video's poster decoded, at the size its tag gives: the frame
        # its description names (animation.poster), else its last frame.
        driver.set_script_timeout(30)
        posters = driver.execute_async_script(
            "const done = arguments[arguments.length - 1];"
            "Promise.all([...document.querySelectorAll('video')].map(v => new Promise(ready => {"
            " const image = new Image();"
            " const tagged = [Number(v.dataset.posterWidth), Number(v.dataset.posterHeight)];"
            " image.onload = () => ready([v.getAttribute('src'), v.getAttribute('poster'), image.naturalWidth,"
            " image.naturalHeight, tagged]);"
            " image.onerror = () => ready([v.getAttribute('src'), v.getAttribute('poster'), 0, 0, tagged]);"
            " image.src = v.poster; }))).then(done);")
        for src, poster, width, height, tagged in posters:
            film = films.get(src, {"size": None})
            expected = film["size"]
            if not poster or not poster.startswith("posters/"):
                failures.append("video %s: its poster is %s, not the poster frame posters/ID.png" % (src, poster))
            elif width <= 0:
                failures.append("video %s: its poster %s did not load" % (src, poster))
            elif [width, height] != expected or [width, height] != tagged:
                failures.append("video %s: its poster %s is %dx%d, its tag says %s, its metadata %s"
                                % (src, poster, width, height, tagged, expected))
        # Every film's card shows its animated preview where the film is,
        # until the film is opened to play: the preview loaded at the size
        # its metadata gives, animated, shown, and the <video> not shown
        # yet; once opened, the <video> is shown (with its poster frame) and
        # the preview is not.
        failures += film_previews(driver, films)
        # The whole page in one picture: a window as tall as the page, every
        # card's parameters, numbers and notes open, every film showing its
        # preview as a visitor first sees it.
        driver.execute_script("document.querySelectorAll('details:not(.film)').forEach(d => d.open = true);")
        driver.set_window_size(1280, 600)
        height, chrome = driver.execute_script(
            "return [document.documentElement.scrollHeight, window.outerHeight - window.innerHeight];")
        driver.set_window_size(1280, min(height + chrome, 16000))
        time.sleep(0.5)
        driver.save_screenshot(args.screenshot)
        # Seeking to the end checks the film is seekable (its index is good).
        driver.execute_script("document.querySelectorAll('details.film').forEach(d => d.open = true);")
        driver.execute_script("document.querySelectorAll('video').forEach(v => {"
                              " v.preload = 'auto'; v.currentTime = Math.max(0, v.duration - 0.05); });")
        wait_for(driver, "return [...document.querySelectorAll('video')].every(v => (v.readyState >= 2"
                 " && !v.seeking) || v.error)", seconds=10)
        for src, duration, position in driver.execute_script(
                "return [...document.querySelectorAll('video')].map(v => [v.getAttribute('src'), v.duration,"
                " v.currentTime]);"):
            if duration and abs(position - (duration - 0.05)) > 0.1:
                failures.append("video %s did not seek to its end (%.2f s): it stays at %.2f s"
                                % (src, duration - 0.05, position))
        # A phone: one column, nothing wider than the screen.
        driver.set_window_size(390, 844)
        time.sleep(0.3)
        wide = driver.execute_script("return [document.documentElement.scrollWidth, window.innerWidth];")
        if wide[0] > wide[1]:
            failures.append("on a phone-wide window (%d px) the page is %d px wide" % (wide[1], wide[0]))
        driver.save_screenshot(args.screenshot.replace(".png", "-phone.png"))
        for entry in driver.get_log("browser"):
            if entry["level"] in ("SEVERE", "WARNING"):
                failures.append("console: %s" % entry["message"])
        # Each figure's SVG that its card links to, opened on its own: an SVG
        # document of the figure's size whose images all decoded, and not a
        # message in the console.
        driver.set_window_size(1280, 2400)
        svgs = 0
        for figure in figures:
            with open(os.path.join(args.out, figure + ".json")) as f:
                meta = json.load(f)
            if "svg" not in meta.get("vector", {}):
                continue
            svgs += 1
            driver.get(url.replace("index.html", meta["vector"]["svg"]["file"]))
            wait_for(driver, "return document.readyState == 'complete';", seconds=10)
            root = driver.execute_script(
                "const r = document.documentElement; return [r.localName, r.getAttribute('width'),"
                " r.getAttribute('height'), [...document.querySelectorAll('image')].length];")
            width, height = meta["image"]["size"]
            if root[:3] != ["svg", "%dpx" % width, "%dpx" % height]:
                failures.append("%s.svg opens as %s, not an SVG of %d x %d px" % (figure, root[:3], width, height))
            for entry in driver.get_log("browser"):
                failures.append("console on %s.svg: %s" % (figure, entry["message"]))
        if args.figgen and svgs == 0:
            failures.append("no figure has an SVG to open")
    finally:
        driver.quit()
        server.shutdown()
        shutil.rmtree(profile, ignore_errors=True)

    for failure in failures:
        print("gallery_in_browser: " + failure)
    if not failures:
        print("gallery_in_browser: %d images and %d videos loaded, no console messages; screenshots %s"
              % (len(images), len(videos), args.screenshot))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
