"""test_viewer.py: the replay viewer (build/rigid SCRIPT.lua --html FILE) in headless
Chromium.  Run by `make test` when a browser is installed:

    python3 tests/viewer/test_viewer.py --host build/rigid --out build/viewer-tests

What it proves, each as one named check:
  * the platformer's page at #frame=0 and #frame=K draws the player where the physics put it:
    the truth is the script's own printed position (print -> stdout, not the recording), the
    pixels are the screenshot's, the transform is the page's worldToPage; and the player
    stands on the ground's top edge in pixels at frame 0;
  * the log shows the printed line in step with the frame it was printed at;
  * arrow keys step one frame, hovering the player names it with its position;
  * the page makes no network request (the DevTools protocol sees every request; a page that
    does request something is caught, so the check can fail) and its text refers to nothing
    outside itself;
  * rain.lua with 4000 circles over 600 steps makes a file under 10 MB that the page reads;
  * scenes that churn bodies, shapes, names and the log (tests/viewer/scenes) replay whole.
Closes with "N passed, N failed".
"""
import json
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from browser import Browser, png_pixels  # noqa: E402
from checks import check, finish, host_and_out  # noqa: E402

OFF = "&trails=0&names=0&contacts=0&velocities=0"   # shapes only: clean pixels


def record(host, script, html, args=()):
    out = subprocess.run([host, script, "--html", html] + list(args), capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError("%s failed:\n%s%s" % (script, out.stdout, out.stderr))
    return out.stdout


def meta_of(html):
    text = open(html, encoding="utf-8").read()
    m = re.search(r'<script id="rigid-meta" type="application/json">(.*?)</script>', text, re.S)
    return json.loads(m.group(1)), text


def blend(rgba, bg=(0xf7, 0xf7, 0xf4)):
    """The pixel a fill of 0xRRGGBBAA makes over the canvas background."""
    a = (rgba & 255) / 255
    return tuple(round(((rgba >> s) & 255) * a + c * (1 - a)) for s, c in zip((24, 16, 8), bg))


def find_colour(rows, colour, tol=3):
    """Pixels within tol of colour in every channel: (count, centroid, bounding box)."""
    n = sx = sy = 0
    box = [10**9, 10**9, -1, -1]
    for y, row in enumerate(rows):
        for x, p in enumerate(row):
            if abs(p[0] - colour[0]) <= tol and abs(p[1] - colour[1]) <= tol and abs(p[2] - colour[2]) <= tol:
                n += 1
                sx += x
                sy += y
                box = [min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
    return n, (sx / n + 0.5, sy / n + 0.5) if n else None, box


def canvas_shot(page):
    """The screenshot of the canvas alone, and its page position."""
    r = page.eval("(function () { const r = document.getElementById('view').getBoundingClientRect();"
                  " return [r.left + scrollX, r.top + scrollY, r.width, r.height]; })()")
    data = page.call("Page.captureScreenshot", format="png",
                     clip={"x": r[0], "y": r[1], "width": r[2], "height": r[3], "scale": 1})["data"]
    import base64
    _, _, rows = png_pixels(base64.b64decode(data))
    return rows, r


def open_frame(b, url, frame):
    page = b.open(url)
    page.wait("document.body.dataset.ready === '1' && +document.body.dataset.frame === %d" % frame)
    page.eval("new Promise(function (ok) { requestAnimationFrame(function () { requestAnimationFrame(ok); }); })", True)
    return page


def test_platformer(b, host, out):
    html = os.path.join(out, "run.html")
    printed = record(host, "lua/examples/platformer.lua", html)
    meta, text = meta_of(html)
    # The script's own lines: "t =  2.0 s  x = 11.10  y =  1.45 ..." -> (t, x, y)
    truth = [(float(m.group(1)), float(m.group(2)), float(m.group(3)))
             for m in re.finditer(r"t = +([\d.]+) s +x = +(-?[\d.]+) +y = +(-?[\d.]+)", printed)]
    check(len(truth) >= 3, "the platformer prints the player's position", printed[:300])
    # The frame each line was printed at, as the page logs it; the host's rule is that a line
    # printed in update() before step s sees frame s - 1, and setup's lines frame 0.
    stamps = {}
    for frame, line in meta["log"]:
        m = re.match(r"t = +([\d.]+) s", line)
        if m:
            stamps[float(m.group(1))] = frame
    want = {t: (0 if t == 0 else round(t * 60) - 1) for t, _, _ in truth}
    check(all(stamps.get(t) == f for t, f in want.items()),
          "each printed line is logged at the frame it saw (setup: 0, update before step s: s - 1)",
          "page %s, host rule %s" % (stamps, want))
    player = [c for c in meta["colors"] if c[1] & 4]   # the colour drawn for awake dynamic bodies
    static = [c for c in meta["colors"] if c[1] & 1]
    if not check(len(player) == 1 and len(static) == 1, "one colour for awake dynamic bodies, one for static",
                 str(meta["colors"])):
        return
    pcol, scol = blend(player[0][0]), blend(static[0][0])
    url = "file://" + os.path.abspath(html)
    centres = {}
    for t, x, y in (truth[0], truth[2]):   # the start, and t = 2 s in the air
        frame = stamps[t]
        page = open_frame(b, url + "#frame=%d%s" % (frame, OFF), frame)
        rows, rect = canvas_shot(page)
        s = page.eval("rigidViewer.scale()")
        ex, ey = page.eval("rigidViewer.worldToPage(%r, %r)" % (x, y))
        ex, ey = ex - rect[0], ey - rect[1]
        n, c, box = find_colour(rows, pcol)
        # Tolerance: the printed position is rounded to 0.005 m (0.005 s px); the centroid of
        # the interior pixels of an axis-aligned box is its centre to half a pixel.
        tol = 0.5 + 0.005 * s + 0.25
        ok = c is not None and abs(c[0] - ex) <= tol and abs(c[1] - ey) <= tol
        check(ok, "frame %d: the player is drawn at the printed (%.2f, %.2f) m: pixel (%.1f, %.1f)"
              % (frame, x, y, ex, ey), "found %d pixels of %s, centroid %s, box %s, tolerance %.2f px"
              % (n, pcol, c, box, tol))
        # 0.7 x 1 m, less its one-pixel outline on each side
        w, h = box[2] - box[0] + 1, box[3] - box[1] + 1
        check(abs(w - (0.7 * s - 2)) <= 1.5 and abs(h - (1.0 * s - 2)) <= 1.5,
              "frame %d: the player's box is 0.7 x 1 m on screen (%.0f x %.0f px)" % (frame, 0.7 * s, s),
              "interior %d x %d px" % (w, h))
        centres[frame] = c
        if t == 0:
            # On the ground: the first ground pixel below the player is the ground's top y = 0.
            col = int(round(c[0]))
            below = [yy for yy in range(box[3] + 1, len(rows))
                     if all(abs(rows[yy][col][i] - scol[i]) <= 3 for i in range(3))]
            gy = page.eval("rigidViewer.worldToPage(0, 0)")[1] - rect[1]
            check(below and box[3] < below[0] and abs(below[0] - gy) <= 2.5,
                  "frame 0: the player stands on the ground's top edge (pixel row %.1f)" % gy,
                  "player's lowest interior row %d, ground from row %s" % (box[3], below[:1]))
        else:
            now = page.eval("(document.querySelector('#log .now') || {}).textContent || ''")
            check(re.search(r"t = +%.1f s" % t, now) is not None,
                  "frame %d: the log's current line is the one printed then" % frame, repr(now))
            page.call("Input.dispatchKeyEvent", type="keyDown", key="ArrowRight", code="ArrowRight",
                      windowsVirtualKeyCode=39)
            page.call("Input.dispatchKeyEvent", type="keyUp", key="ArrowRight", code="ArrowRight",
                      windowsVirtualKeyCode=39)
            page.wait("rigidViewer.frame() === %d" % (frame + 1), 5)
            check(True, "the right arrow steps one frame (%d -> %d)" % (frame, frame + 1))
            page.call("Input.dispatchKeyEvent", type="keyDown", key="ArrowLeft", code="ArrowLeft",
                      windowsVirtualKeyCode=37)
            page.wait("rigidViewer.frame() === %d" % frame, 5)
            hx, hy = page.eval("rigidViewer.worldToPage(%r, %r)" % (x, y))
            page.call("Input.dispatchMouseEvent", type="mouseMoved", x=hx, y=hy)
            page.wait("!document.getElementById('tip').hidden", 5)
            tip = page.eval("document.getElementById('tip').textContent")
            check("player" in tip and ("x = %.2f" % x)[:-1] in tip.replace("x =  ", "x = "),
                  "hovering the player shows its name and position", repr(tip))
    check(len(centres) == 2 and abs(list(centres.values())[0][0] - list(centres.values())[1][0]) > 20,
          "#frame=K shows another moment than #frame=0 (the player moved on screen)")


def test_no_network(b, out, html):
    _, text = meta_of(html)
    urls = [u for u in b.requests if not u.startswith("about:")]
    page_url = "file://" + os.path.abspath(html)
    check(urls and all(u.split("#")[0] == page_url for u in urls),
          "the viewer requested nothing but its own file", "\n      ".join(urls))
    refs = re.findall(r"(?i)https?:|\b(?:src|href|action)\s*=|url\(|@import|<link\b|<iframe|"
                      r"\bfetch\s*\(|XMLHttpRequest|WebSocket|EventSource|sendBeacon|import\s*\(", text)
    check(not refs, "the page's text refers to nothing outside it", str(refs[:5]))
    # The check can fail: a page with one outside reference is seen requesting it.
    leak = os.path.join(out, "leak.html")
    with open(leak, "w") as f:
        f.write('<!doctype html><body><img src="http://rigid.invalid/pixel.png"><script>'
                'document.body.dataset.ready = "1";</script>')
    before = len(b.requests)
    page = b.open("file://" + os.path.abspath(leak))
    page.wait("document.body.dataset.ready === '1'")
    time.sleep(0.5)
    check(any("rigid.invalid" in u for u in b.requests[before:]),
          "a page that does request something is caught (the network check can fail)")


def test_rain(b, host, out):
    html = os.path.join(out, "rain.html")
    record(host, "lua/examples/rain.lua", html, ["--steps", "600"])
    size = os.path.getsize(html)
    check(size < 10 * 1000 * 1000, "rain 4000 over 600 steps: %.2f MB, under 10 MB" % (size / 1e6))
    page = b.open("file://" + os.path.abspath(html) + "#frame=300")
    page.wait("document.body.dataset.ready === '1' || document.body.dataset.error", 120)
    err = page.eval("document.body.dataset.error || ''")
    meta, _ = meta_of(html)
    check(not err and page.eval("rigidViewer.frames") == 601 and len(meta["tracks"]) == 4003,
          "the page reads all 601 frames of the 4003 bodies", err)


def test_scenes(b, host, out):
    """Scenes that make the recorder work: bodies made, destroyed, reshaped and moved, names
    with markup and broken UTF-8, a spring, an error inside print; a log past its cap; a
    script that steps its own world."""
    here = os.path.dirname(os.path.abspath(__file__))
    for name, frames in (("churn", 121), ("chatter", 31), ("plain", 30)):
        html = os.path.join(out, name + ".html")
        record(host, os.path.join(here, "scenes", name + ".lua"), html)
        page = b.open("file://" + os.path.abspath(html) + "#frame=%d" % (frames - 1))
        page.wait("document.body.dataset.ready === '1' || document.body.dataset.error", 60)
        err = page.eval("document.body.dataset.error || ''")
        check(not err and page.eval("rigidViewer.frames") == frames,
              "%s: the page reads its %d frames" % (name, frames), err)
        meta, _ = meta_of(html)
        if name == "churn":
            names = page.eval("Array.prototype.map.call(document.getElementById('body').options, function (o) { return o.textContent; })")
            check(any("</script><script>" in n for n in names) and any("bad \ufffd\ufffd bytes \ufffd" in n for n in names),
                  "churn: a name with markup is shown as text, bytes that are not UTF-8 as U+FFFD", str(names))
            drops = [t for t in meta["tracks"] if (t[0] or "").startswith("drop ")]
            check(len(drops) == 24 and sum(1 for t in drops if t[5] < frames - 1) == 10,
                  "churn: 24 bodies dropped in, 10 destroyed before the end", str([t[4:6] for t in drops]))
            check(meta["recorded"]["springs"], "churn: the spring is recorded")
            logged = [l[1] for l in meta["log"]]
            check("a line with a tab\tand a NUL \u0000 inside" in logged and "before the error" in logged,
                  "churn: printed lines logged as printed (a tab, a NUL; the part before an error)", str(logged))
        elif name == "chatter":
            check(meta["log_dropped"] > 0 and "not kept" in page.eval("document.getElementById('subtitle').textContent"),
                  "chatter: the log stops at its cap and the page says how many lines it dropped (%d)" % meta["log_dropped"])


def main():
    a = host_and_out()
    with Browser() as b:
        for name, test in (("platformer", lambda: test_platformer(b, a.host, a.out)),
                           ("no network", lambda: test_no_network(b, a.out, os.path.join(a.out, "run.html"))),
                           ("rain", lambda: test_rain(b, a.host, a.out)),
                           ("scenes", lambda: test_scenes(b, a.host, a.out))):
            try:
                test()
            except Exception as e:   # a wait that timed out, a run that failed: a failure
                check(False, "%s: ran to the end" % name, "%s: %s" % (type(e).__name__, e))
        for line in b.console:
            check(False, "the page logs no error", line)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
