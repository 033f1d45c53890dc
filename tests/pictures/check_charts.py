"""check_charts.py: every accuracy chart held against the CSV it is drawn from.

    python3 tests/pictures/check_charts.py --csv DIR --tables DIR

DIR of --csv holds the lab's CSV (build/accuracy --out DIR, float and double); --tables the
points gnuplot plots for each chart (tools/charts/accuracy.gp with check=DIR: table mode, the
points of every curve in order, blank lines where a line is broken).  For each chart this
restates, from the CSV alone, what every curve must show: which rows, which columns, in which
order, and checks that the curve shows exactly that:
  * each series' points are its rows' values (to the 6 digits gnuplot writes), none missing,
    none extra, none from another series;
  * a series drawn as a line is one unbroken line;
  * a series drawn as points has none outside the axes (they would vanish unseen);
  * the Pareto front is the set of runs no other run beats on both cost and error, worked
    out here, sorted by cost, one line; and the lab's pareto column says the same.
Closes with "N passed, N failed".
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import checks  # noqa: E402

IGS = ["explicit_euler", "semi_implicit_euler", "verlet", "rk4"]
SCENES = ["oscillator", "damped_oscillator", "projectile_linear_drag", "fall_quadratic_drag",
          "throw_up_quadratic_drag", "slide_friction"]


def check(ok, name, detail=""):
    """A check of the chart being checked: quiet when it passes (the chart gets one line)."""
    return checks.check(ok, name, detail, quiet=True)


def read_csv(d, name):
    with open(os.path.join(d, name)) as f:
        return list(csv.DictReader(f))


def num(s):
    return float(s)


def read_table(path):
    """gnuplot's table output: a list of plots, each a list of curves {title, segments}."""
    plots, curve = [], None
    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if line.startswith("# Curve ") and " of " in line:
                k = int(line.split()[2])
                if k == 0:
                    plots.append([])
                curve = {"title": None, "segments": [[]]}
                plots[-1].append(curve)
            elif line.startswith("# Curve title:"):
                curve["title"] = line.split(":", 1)[1].strip().strip('"')
            elif line.startswith("#"):
                continue
            elif not line.strip():
                if curve and curve["segments"][-1]:
                    curve["segments"].append([])
            elif curve is not None:
                p = line.split()
                curve["segments"][-1].append((float(p[0]), float(p[1]), p[-1]))
    return plots


def close(a, b):
    return abs(a - b) <= 1e-5 * max(abs(a), abs(b)) + 1e-300


def shown(curve):
    """The points drawn (in range or clipped by the axes), in order; and the segments that hold any."""
    def drawn(p):
        return p[2] in ("i", "o") and p[0] == p[0] and p[1] == p[1]
    pts = [p for seg in curve["segments"] for p in seg if drawn(p)]
    segs = [seg for seg in curve["segments"] if any(drawn(p) for p in seg)]
    return pts, segs


def series(name, curve, want, line=True, clipped=False):
    """clipped: the series may leave the axes (a line that runs off the chart, seen leaving it)."""
    pts, segs = shown(curve)
    same = len(pts) == len(want) and all(close(p[0], w[0]) and close(p[1], w[1]) for p, w in zip(pts, want))
    detail = ""
    if not same:
        bad = next((i for i, (p, w) in enumerate(zip(pts, want)) if not (close(p[0], w[0]) and close(p[1], w[1]))),
                   min(len(pts), len(want)))
        detail = "%d points drawn, %d rows; first difference at %d: drawn %s, row %s" % (
            len(pts), len(want), bad, pts[bad][:2] if bad < len(pts) else None, want[bad] if bad < len(want) else None)
    check(same, name + ": its rows, in order", detail)
    if line:
        check(len(segs) <= 1, name + ": one unbroken line", "%d pieces" % len(segs))
    if not clipped:
        out = [p for p in pts if p[2] == "o"]
        check(not out, name + ": no point outside the axes (none hidden)", str(out[:3]))


def rows_of(rows, **eq):
    return [r for r in rows if all(r[k] == str(v) for k, v in eq.items())]


def finite_error(r):
    e = num(r["error"])
    return 0 < e < 1e30


def front(rows):
    """The runs no other run beats: as cheap or cheaper, and as accurate or more, one of them
    strictly.  Errors within a millionth are the same (the CSV holds six digits)."""
    ok = [r for r in rows if num(r["error"]) < math.inf]
    out = []
    for p in ok:
        pc, pe = num(p["cost_ns_per_body_s"]), num(p["error"])

        def beats(q):
            qc, qe = num(q["cost_ns_per_body_s"]), num(q["error"])
            tie = 1e-6 * max(qe, pe)
            better, same = qe < pe - tie, abs(qe - pe) <= tie
            return q is not p and qc <= pc and (better or same) and (qc < pc or better)
        if not any(beats(q) for q in ok):
            out.append(p)
    return sorted(out, key=lambda r: num(r["cost_ns_per_body_s"]))


def expect_plots(chart, plots, n):
    check(len(plots) == n, "%s: %d panels drawn" % (chart, n), "found %d" % len(plots))
    return len(plots) == n


def pareto(d, plots):
    rows = read_csv(d, "sweep_double.csv")
    if not expect_plots("pareto", plots, 6):
        return
    for sc, plot in zip(SCENES, plots):
        mine = rows_of(rows, scene=sc)
        for j, ig in enumerate(IGS):
            want = [(num(r["cost_ns_per_body_s"]), num(r["error"])) for r in rows_of(mine, integrator=ig) if finite_error(r)]
            # explicit Euler's spring errors (up to 10^5) run off the top: a line seen leaving
            series("pareto %s %s" % (sc, ig), plot[j], want, clipped=True)
        best = front(mine)
        flagged = [r for r in mine if r["pareto"] == "1"]
        check(sorted(id(r) for r in best) == sorted(id(r) for r in flagged),
              "pareto %s: the CSV's front is the runs nothing beats" % sc,
              "worked out %d, flagged %d" % (len(best), len(flagged)))
        series("pareto %s front" % sc, plot[4],
               [(num(r["cost_ns_per_body_s"]), num(r["error"])) for r in best], clipped=True)
        series("pareto %s 60 Hz" % sc, plot[5],
               [(num(r["cost_ns_per_body_s"]), num(r["error"])) for r in rows_of(mine, rate_hz=60) if finite_error(r)],
               line=False)


def convergence(d, plots):
    if not expect_plots("convergence", plots, 6):
        return
    for sc, plot in zip(SCENES, plots):
        for k, real in enumerate(("double", "float")):
            rows = rows_of(read_csv(d, "sweep_%s.csv" % real), scene=sc)
            for j, ig in enumerate(IGS):
                want = [(num(r["dt"]), num(r["error"])) for r in rows_of(rows, integrator=ig) if finite_error(r)]
                series("convergence %s %s %s" % (sc, ig, real), plot[4 * k + j], want, clipped=True)


def energy60(d, plots):
    rows = rows_of(read_csv(d, "energy60_double.csv"), scene="oscillator")
    if not expect_plots("energy60", plots, 2):
        return
    for j, ig in enumerate(IGS):
        series("energy60 %s" % ig, plots[0][j], [(num(r["t"]), num(r["energy_ratio"])) for r in rows_of(rows, integrator=ig)])
    for j, ig in enumerate(IGS[1:]):
        series("energy60 %s - 1" % ig, plots[1][j],
               [(num(r["t"]), num(r["energy_ratio"]) - 1) for r in rows_of(rows, integrator=ig)])


def dissipation(d, plots):
    rows = read_csv(d, "dissipation_double.csv")
    if not expect_plots("dissipation", plots, 2):
        return
    for force, plot in zip(("friction", "drag"), plots):
        for j, m in enumerate(["naive"] + IGS):
            series("dissipation %s %s" % (force, m), plot[j],
                   [(num(r["r"]), num(r["v_after"])) for r in rows_of(rows, force=force, method=m)])
        if force == "drag":
            pts, _ = shown(plot[5])
            check(pts and all(close(p[1], 1 / (1 + p[0])) for p in pts), "dissipation drag: the exact curve is 1/(1 + r)")


def framerate(d, plots):
    rows = read_csv(d, "framerate_double.csv")
    if not expect_plots("framerate", plots, 1):
        return
    plot = plots[0]
    for j, ig in enumerate(IGS[:3]):
        steady = rows_of(rows, pattern="steady", integrator=ig)
        series("framerate %s per frame" % ig, plot[j], [(num(r["frame_rate_hz"]), num(r["naive_apex"])) for r in steady])
        series("framerate %s accumulated" % ig, plot[3 + j], [(num(r["frame_rate_hz"]), num(r["fixed_apex"])) for r in steady])
        series("framerate %s jittered" % ig, plot[6 + j],
               [(num(r["frame_rate_hz"]), num(r["naive_apex"])) for r in rows_of(rows, pattern="jitter", integrator=ig)],
               line=False)
    series("framerate exact", plot[9], [(num(r["frame_rate_hz"]), num(r["exact"])) for r in rows_of(rows, pattern="steady", integrator="rk4")])


def stability(d, plots):
    growth = read_csv(d, "growth_double.csv")
    if not expect_plots("stability", plots, 2):
        return
    for j, ig in enumerate(IGS):
        g = rows_of(growth, integrator=ig)
        series("stability %s growth" % ig, plots[0][j], [(num(r["z"]), num(r["growth"])) for r in g], line=False)
        series("stability %s theory" % ig, plots[0][4 + j], [(num(r["z"]), num(r["theory"])) for r in g])
    # bars at 0..3 under the tick labels explicit Euler, semi-implicit Euler, Verlet, RK4
    for k, (name, col) in enumerate((("double", "boundary"), ("float", "boundary"), ("double", "theory"))):
        rows = read_csv(d, "stability_%s.csv" % name)
        check([r["integrator"] for r in rows] == IGS, "stability bars: rows in the order of the tick labels")
        series("stability bars %s %s" % (name, col), plots[1][k], [(float(i), num(r[col])) for i, r in enumerate(rows)], line=False)


def tunnel(d, plots):
    rows = read_csv(d, "tunnel_double.csv")
    if not expect_plots("tunnel", plots, 1):
        return
    for j, m in enumerate(("lab_naive", "discrete", "continuous")):
        mine = rows_of(rows, method=m)
        series("tunnel %s measured" % m, plots[0][2 * j], [(num(r["speed"]), num(r["fraction"])) for r in mine],
               line=False)
        series("tunnel %s theory" % m, plots[0][2 * j + 1], [(num(r["speed"]), num(r["theory"])) for r in mine])


def pile(d, plots):
    rows = read_csv(d, "pile_double.csv")
    if not expect_plots("pile", plots, 1):
        return
    # a sink of exactly 0 on the floor line at 1e-16; integrator j's points at 1 + 0.025 (j - 1.5) x
    for k, (ratio, it) in enumerate(((100, 0), (100, 64), (1, 0))):
        for j, ig in enumerate(IGS):
            series("pile %s ratio %d, %d iterations" % (ig, ratio, it), plots[0][4 * k + j],
                   [(num(r["rate_hz"]) * (1 + 0.025 * (j - 1.5)), num(r["max_err"]) if num(r["max_err"]) > 0 else 1e-16)
                    for r in rows_of(rows, integrator=ig, ratio=ratio, iterations=it)])


CHARTS = {"pareto": pareto, "convergence": convergence, "energy60": energy60, "dissipation": dissipation,
          "framerate": framerate, "stability": stability, "tunnel": tunnel, "pile": pile}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True)
    ap.add_argument("--tables", required=True)
    a = ap.parse_args()
    for name in CHARTS:
        before = dict(checks.counts)
        report(name, a)
        if checks.counts["failed"] == before["failed"]:
            print("ok    %s: %d checks of its curves against its CSV" % (name, checks.counts["passed"] - before["passed"]))
    return checks.finish()


def report(name, a):
    path = os.path.join(a.tables, name + ".table")
    if not os.path.exists(path):
        # the collision charts exist when the lab was built with collision
        check(name in ("tunnel", "pile") and not os.path.exists(os.path.join(a.csv, name + "_double.csv")),
              "%s: drawn (its table exists)" % name)
        return
    try:
        CHARTS[name](a.csv, read_table(path))
    except (KeyError, IndexError, ValueError) as e:
        check(False, "%s: the chart and its CSV could be matched" % name, "%s: %s" % (type(e).__name__, e))


if __name__ == "__main__":
    sys.exit(main())
