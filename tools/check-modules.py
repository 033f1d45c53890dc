#!/usr/bin/env python3
"""Library modules that call each other in a circle, from `nm -A` of the static library.

A module is one object file of librigid.a; module A uses B when A has an undefined symbol
that B defines.  Prints every pair of modules that reach each other and exits 1 if there is
one; prints the modules by layer (each above all it uses) otherwise.
Usage: check-modules.py build/librigid.a"""
import collections
import subprocess
import sys


def main(lib):
    out = subprocess.run(["nm", "-A", lib], capture_output=True, text=True, check=True).stdout
    defs, uses, mods = {}, collections.defaultdict(set), set()
    for line in out.splitlines():
        p = line.split()
        if len(p) < 2:
            continue
        mod = p[0].split(":")[1] if ":" in p[0] else p[0]
        mods.add(mod)
        kind, sym = (p[1], p[2]) if len(p) == 3 else (p[-2], p[-1])
        if kind in "TDBR":
            defs[sym] = mod
        elif kind == "U":
            uses[mod].add(sym)
    graph = {m: {defs[s] for s in uses[m] if s in defs and defs[s] != m} for m in mods}

    def reach(a, b, seen):
        if a == b:
            return True
        seen.add(a)
        return any(reach(n, b, seen) for n in graph[a] if n not in seen)

    circles = sorted({tuple(sorted((a, b))) for a in graph for b in graph[a] if reach(b, a, set())})
    if circles:
        for a, b in circles:
            print("circle: %s <-> %s" % (a, b))
        return 1
    layer = {}

    def depth(m):
        if m not in layer:
            layer[m] = 1 + max((depth(n) for n in graph[m]), default=0)
        return layer[m]

    for m in mods:
        depth(m)
    for d in sorted(set(layer.values()), reverse=True):
        print("layer %d: %s" % (d, " ".join(sorted(m[:-2] for m in mods if layer[m] == d))))
    print("%d modules, no circle" % len(mods))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
