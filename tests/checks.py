"""checks.py: the named checks of our Python test runners, counted for the closing line
"N passed, N failed".  A check that fails prints its detail."""
import sys

counts = {"passed": 0, "failed": 0}


def check(ok, name, detail="", quiet=False):
    """Counts one check; prints it (a pass only when not quiet).  Returns ok."""
    if ok:
        counts["passed"] += 1
        if not quiet:
            print("ok    " + name)
    else:
        counts["failed"] += 1
        print("FAIL  " + name + ("\n      " + detail if detail else ""))
    return ok


def finish():
    """Prints the closing line; the exit status: 1 when any check failed."""
    print("%d passed, %d failed" % (counts["passed"], counts["failed"]))
    sys.stdout.flush()
    return 1 if counts["failed"] else 0


def host_and_out():
    """The arguments of a runner that drives build/rigid: --host HOST --out DIR (made)."""
    import argparse
    import os
    ap = argparse.ArgumentParser()
    ap.add_argument("--host", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    return a
