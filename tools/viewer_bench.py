"""viewer_bench.py: the replay viewer in headless Chromium, for `make bench` and the README.

    viewer_bench.py --fps PAGE.html [--seconds S]   size, time to read, frame rate playing
    viewer_bench.py --shot 'PAGE.html#frame=K' OUT.png   a screenshot of the player
    viewer_bench.py --svg-shot PICTURE.svg OUT.png        an SVG picture as PNG, at its size

The frame rate is the page's own: the requestAnimationFrame timestamps of the frames it drew
while playing at 1x (rigidViewer.stats()).  Not a test: it prints what it measures.
"""
import argparse
import base64
import os
import re
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "viewer"))
from browser import Browser  # noqa: E402


def url_of(path):
    base, _, frag = path.partition("#")
    return "file://" + os.path.abspath(base) + ("#" + frag if frag else "")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--fps")
    ap.add_argument("--seconds", type=float, default=6.0)
    ap.add_argument("--shot", nargs=2, metavar=("PAGE", "PNG"))
    ap.add_argument("--svg-shot", nargs=2, metavar=("SVG", "PNG"))
    a = ap.parse_args()
    with Browser() as b:
        if a.fps:
            t0 = time.time()
            page = b.open(url_of(a.fps))
            page.wait("document.body.dataset.ready === '1' || document.body.dataset.error", 300)
            ready = time.time() - t0
            err = page.eval("document.body.dataset.error || ''")
            if err:
                print("the page cannot read its recording: " + err)
                return 1
            page.eval("rigidViewer.play()")
            time.sleep(a.seconds)
            st = page.eval("rigidViewer.stats()")
            print("%s: %.2f MB, %d frames, read and drawn in %.1f s" % (
                a.fps, os.path.getsize(a.fps) / 1e6, page.eval("rigidViewer.frames"), ready))
            print("playing at 1x: %.1f frames per second over %d frames (interval median %.1f ms, "
                  "longest %.1f ms; drawing median %.1f ms, longest %.1f ms)" % (
                      st["fps"], st["frames"], st["interval_p50_ms"], st["interval_max_ms"],
                      st["draw_p50_ms"], st["draw_max_ms"]))
        if a.shot:
            page = b.open(url_of(a.shot[0]), width=1480, height=900)
            page.wait("document.body.dataset.ready === '1'", 60)
            time.sleep(0.3)
            h = page.eval("document.getElementById('main').getBoundingClientRect().bottom + 8")
            png = page.call("Page.captureScreenshot", format="png",
                            clip={"x": 0, "y": 0, "width": 1480, "height": h, "scale": 1})["data"]
            with open(a.shot[1], "wb") as f:
                f.write(base64.b64decode(png))
            print("wrote " + a.shot[1])
        if a.svg_shot:
            text = open(a.svg_shot[0]).read(2000)
            w = float(re.search(r'width="([\d.]+)"', text).group(1))
            h = float(re.search(r'height="([\d.]+)"', text).group(1))
            page = b.open(url_of(a.svg_shot[0]), width=int(w + 0.5), height=int(h + 0.5))
            page.wait("document.readyState === 'complete'", 30)
            png = page.call("Page.captureScreenshot", format="png",
                            clip={"x": 0, "y": 0, "width": w, "height": h, "scale": 1})["data"]
            with open(a.svg_shot[1], "wb") as f:
                f.write(base64.b64decode(png))
            print("wrote " + a.svg_shot[1])
    return 0


if __name__ == "__main__":
    sys.exit(main())
