#!/usr/bin/python3
"""The gallery checked in a real browser: Debian's headless Chromium, driven
through chromedriver (python3-selenium), over a gallery served on a loopback
port.

    gallery_in_browser.py --figgen build/figgen --out DIR --screenshot FILE.png

renders a few figures into DIR (one with a film, one without), writes the
gallery, serves DIR on 127.0.0.1 and checks in the browser that every image
has loaded (natural size > 0, the size in its tag), every video has loaded
its metadata (duration > 0, the frame count over the fps of its metadata, its
size), nothing was logged to the console, and a phone-wide window needs no
sideways scrolling. Saves a desktop and a phone screenshot. Exits 0 when all
holds, 1 with one line per failure otherwise.
"""
import argparse
import functools
import http.server
import json
import os
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
    def log_message(self, *args):
        pass


def render(figgen, out):
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    subprocess.run([figgen, "render", *FIGURES, "--scale", "0.5", "--out", out], check=True)
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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--figgen", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--screenshot", required=True)
    args = parser.parse_args()
    render(args.figgen, args.out)

    server = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), functools.partial(QuietHandler, directory=args.out))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = "http://127.0.0.1:%d/index.html" % server.server_address[1]

    failures = []
    profile = tempfile.mkdtemp(prefix="figgen-chromium-")
    driver = browser(profile)
    try:
        driver.get(url)
        wait_for(driver, "return document.readyState === 'complete'")
        # Every image decoded; its natural size is the one its tag gives.
        images = driver.execute_script(
            "return [...document.images].map(i => [i.getAttribute('src'), i.complete, i.naturalWidth,"
            " i.naturalHeight, +i.getAttribute('width'), +i.getAttribute('height')]);")
        if len(images) != len(FIGURES):
            failures.append("%d images on the page, expected %d" % (len(images), len(FIGURES)))
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
        filmed = [f for f in FIGURES if "file" in json.load(open(os.path.join(args.out, f + ".json"))).get("animation", {})]
        if len(videos) != len(filmed):
            failures.append("%d videos on the page, expected %d" % (len(videos), len(filmed)))
        for src, duration, width, height, error in videos:
            film = json.load(open(os.path.join(args.out, src.replace(".mp4", ".json"))))["animation"]
            if error:
                failures.append("video %s: media error %d" % (src, error))
                continue
            expected = film["frames"] / film["fps"]
            if not duration or duration <= 0 or abs(duration - expected) > 1.5 / film["fps"]:
                failures.append("video %s lasts %s s, its metadata says %d frames at %d fps (%.3f s)"
                                % (src, duration, film["frames"], film["fps"], expected))
            if [width, height] != film["size"]:
                failures.append("video %s is %dx%d, its metadata says %s" % (src, width, height, film["size"]))
        driver.save_screenshot(args.screenshot)
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
