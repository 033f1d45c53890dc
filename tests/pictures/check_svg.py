"""check_svg.py: the pictures of build/rigid SCRIPT.lua --svg FILE say what the world was at
the moment they show.  For every example it draws (the script's own run):

  * it draws exactly the bodies alive at the end (as many as the subtitle counts);
  * every contact mark sits where two bodies touch: within 2 px of two of the bodies drawn
    (not in mid-air along a path, where a contact of an earlier moment would be);
  * no label lies on a body (its text box, under-estimated, overlaps no body's box);
  * all text, the legend too, fits in the picture's width and height.

    python3 tests/pictures/check_svg.py --host build/rigid --out build/picture-check
Closes with "N passed, N failed".
"""
import glob
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from checks import check, finish, host_and_out  # noqa: E402

NS = "{http://www.w3.org/2000/svg}"
CONTACT_FILLS = ("rgba(220,40,40,1.000)", "rgba(220,180,30,0.502)")   # RG_COLOR_CONTACT, RG_COLOR_SENSOR
# Advances of Helvetica (and Arial, Liberation Sans, which the pictures fall back to) for ' '
# to '~' in 1/1000 em, from the font's AFM metrics: text boxes as wide as the text drawn.
HELVETICA = [278, 278, 355, 556, 556, 889, 667, 191, 333, 333, 389, 584, 278, 333, 278, 278, 556, 556, 556, 556, 556, 556, 556, 556, 556, 556, 278, 278, 584, 584, 584, 556, 1015, 667, 667, 722, 722, 667, 611, 778, 722, 278, 500, 667, 556, 833, 722, 778, 667, 778, 722, 667, 611, 722, 667, 944, 667, 667, 611, 278, 278, 278, 469, 556, 333, 556, 556, 500, 556, 556, 278, 556, 556, 222, 222, 500, 222, 833, 556, 556, 556, 556, 333, 500, 278, 556, 500, 722, 500, 500, 500, 334, 260, 334, 584]


def text_width(s, px):
    return sum(HELVETICA[ord(c) - 32] if 32 <= ord(c) < 127 else 667 for c in s) * px / 1000


def f(e, k):
    return float(e.get(k))


def bodies_of(root):
    """Shapes drawn at the end: (kind, geometry) in the clipped group, filled, 0.8 px outline;
    rings of bodies without a shape (r 4.5, no fill)."""
    out = []
    for g in root.iter(NS + "g"):
        if g.get("clip-path") is None:
            continue
        for e in g:
            tag = e.tag[len(NS):]
            if tag == "rect" and e.get("stroke-width") == "0.8" and e.get("fill") != "none":
                out.append(("box", f(e, "x"), f(e, "y"), f(e, "x") + f(e, "width"), f(e, "y") + f(e, "height")))
            elif tag == "circle" and e.get("stroke-width") == "0.8" and e.get("fill") != "none":
                out.append(("circle", f(e, "cx"), f(e, "cy"), f(e, "r")))
            elif tag == "circle" and e.get("r") == "4.5" and e.get("fill") == "none" and e.get("stroke-dasharray") is None:
                out.append(("circle", f(e, "cx"), f(e, "cy"), 4.5))
    return out


def distance(b, x, y):
    """Distance from (x, y) to the body's region (0 inside)."""
    if b[0] == "box":
        dx = max(b[1] - x, 0, x - b[3])
        dy = max(b[2] - y, 0, y - b[4])
        return math.hypot(dx, dy)
    return max(math.hypot(x - b[1], y - b[2]) - b[3], 0)


def box_of(b):
    if b[0] == "box":
        return b[1:5]
    return (b[1] - b[3], b[2] - b[3], b[1] + b[3], b[2] + b[3])


def check_picture(name, path):
    root = ET.parse(path).getroot()
    width, height = float(root.get("width")), float(root.get("height"))
    texts = list(root.iter(NS + "text"))
    sub = " ".join(t.text or "" for t in texts if t.get("font-size") == "13")
    bodies = bodies_of(root)
    m = re.search(r"(\d+) bodies at the end", sub)
    check(m is not None and int(m.group(1)) == len(bodies),
          "%s: draws the %s bodies alive at the end" % (name, m.group(1) if m else "?"),
          "drew %d; subtitle %r" % (len(bodies), sub))
    marks = [(f(e, "cx"), f(e, "cy")) for g in root.iter(NS + "g") if g.get("clip-path")
             for e in g if e.tag == NS + "circle" and e.get("fill") in CONTACT_FILLS and e.get("stroke") is None]
    floating = [p for p in marks if sum(1 for b in bodies if distance(b, *p) <= 2.0) < 2]
    check(not floating, "%s: each of its %d contact marks sits where two bodies touch" % (name, len(marks)),
          "%d marks near fewer than two bodies, e.g. %s" % (len(floating), floating[:3]))
    labels = [t for g in root.iter(NS + "g") if g.get("font-size") == "12" and g.get("fill") == "#111"
              for t in g if t.tag == NS + "text"]
    boxes = [box_of(b) for b in bodies]
    on = []
    for t in labels:
        x, y = f(t, "x"), f(t, "y")
        r = (x, y - 8.6, x + text_width(t.text or "", 12), y)   # cap height 0.72 em
        hit = [b for b in boxes if r[0] < b[2] - 0.5 and b[0] + 0.5 < r[2] and r[1] < b[3] - 0.5 and b[1] + 0.5 < r[3]]
        if hit:
            on.append((t.text, hit[0]))
    check(not on, "%s: none of its %d labels lies on a body" % (name, len(labels)), str(on[:3]))
    out = []
    for t in texts:
        x, y = float(t.get("x", 0)), float(t.get("y", 0))
        w = text_width(t.text or "", float(t.get("font-size") or next(
            (g.get("font-size") for g in root.iter(NS + "g") if t in list(g) and g.get("font-size")), 12)))
        left = x - (w if t.get("text-anchor") == "end" else w / 2 if t.get("text-anchor") == "middle" else 0)
        if left < 0 or left + w > width or y > height:
            out.append(t.text)
    # legend items sit in translated groups: their text's x is relative
    for g in root.iter(NS + "g"):
        tr = g.get("transform")
        if not tr or not tr.startswith("translate("):
            continue
        gx, gy = (float(v) for v in tr[len("translate("):-1].split(","))
        for t in g.iter(NS + "text"):
            if gx + float(t.get("x", 0)) + text_width(t.text or "", 12) > width or gy > height:
                out.append(t.text)
    check(not out, "%s: all its text fits in its %.0f x %.0f px" % (name, width, height), str(out[:3]))


def main():
    a = host_and_out()
    for script in sorted(glob.glob("lua/examples/*.lua")):
        name = os.path.basename(script)[:-4]
        svg = os.path.join(a.out, name + ".svg")
        run = subprocess.run([a.host, script, "--svg", svg], capture_output=True, text=True)
        if not check(run.returncode == 0 and os.path.exists(svg), "%s: runs and draws" % name, run.stderr[-500:]):
            continue
        check_picture(name, svg)
    return finish()


if __name__ == "__main__":
    sys.exit(main())
