#!/usr/bin/env python3
"""Time-step stability map of the cubes' water with and without delta-SPH (docs/multihybrid.md,
"delta-SPH"): examples/validation/delta/in.water_dt (a periodic box of the cubes' water at rest
with velocity noise) over a grid of c0, mu and delta, for 0.3 s of physical time at each dt of a
ladder (factor sqrt 2 from 3.125e-6 s to 4e-4 s).

"Stable": the run's stability guards do not stop it and the kinetic energy after 0.3 s is not above
its start (the noise decays or stays). Each (c0, mu, delta) is scanned from the largest dt down
and stops at the first stable one (the smaller ones are taken as stable: cheaper runs first).

    scripts/delta-stability-map.py [--c0 4 8 16] [--mu 0.01 0.1 1] [--delta 0 0.1 0.5] [--tend 0.3]
        [--svg docs/img/delta_stability_map.svg]
Prints one line per run and the table of the largest stable dt.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DECK = os.path.join(ROOT, "examples/validation/delta/in.water_dt")
LADDER = [3.125e-6 * 2 ** (k / 2) for k in range(15)]


def run(binary, c0, mu, delta, dt, tend, work):
    args = [binary, "run", DECK, "-var", "c0", str(c0), "-var", "mu", str(mu), "-var", "delta", str(delta),
            "-var", "dt", "%.6g" % dt, "-var", "tend", str(tend), "-log", "none"]
    p = subprocess.run(args, cwd=work, capture_output=True, text=True)
    text = p.stdout + p.stderr
    start = re.search(r"^START_KE (\S+)", text, re.M)
    final = re.search(r"^FINAL_KE (\S+)", text, re.M)
    if p.returncode != 0 or not final:
        why = re.search(r"run stopped at step \d+[^\n]*", text)
        return False, "stopped" + (": " + why.group(0)[:80] if why else "")
    ratio = float(final.group(1)) / float(start.group(1))
    return ratio <= 1.0, "KE ratio %.3g" % ratio


def svg(results, c0s, mus, deltas, path):
    """One panel per delta: rows (c0, mu), columns dt; green stable, red unstable, light green
    assumed stable (below a stable dt, not run)."""
    cw, ch, left, top, gap = 34, 18, 110, 60, 30
    rows = [(c, m) for c in c0s for m in mus]
    pw = left + cw * len(LADDER)
    width = pw * len(deltas) + gap * (len(deltas) - 1) + 10
    height = top + ch * len(rows) + 90
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="11">' % (width, height),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="10" y="18" font-size="14">Cubes water (periodic box, 0.3 s): stable time steps with and without delta-SPH</text>']
    for p, d in enumerate(deltas):
        x0 = p * (pw + gap)
        out.append('<text x="%d" y="40" font-size="13">%s</text>' % (x0 + left, "no delta-SPH" if d == 0 else "delta = %g (molteni)" % d))
        for k, dt in enumerate(LADDER):
            x = x0 + left + k * cw + cw / 2
            out.append('<text x="%g" y="%d" text-anchor="end" transform="rotate(-60 %g %d)" font-size="9">%.3g</text>' % (x + 4, top + ch * len(rows) + 12, x + 4, top + ch * len(rows) + 12, dt))
        for r, (c, m) in enumerate(rows):
            y = top + r * ch
            out.append('<text x="%d" y="%d" font-size="10">c0 %g, mu %g</text>' % (x0 + 4, y + 13, c, m))
            for k, dt in enumerate(LADDER):
                st = results.get((c, m, d, k))
                color = {True: "#3a3", False: "#d33", None: "#bdb"}[st]
                out.append('<rect x="%d" y="%d" width="%d" height="%d" fill="%s" stroke="white"/>' % (x0 + left + k * cw, y, cw, ch, color))
            # the paper's 5e-5 s
        kp = LADDER.index(min(LADDER, key=lambda t: abs(t - 5e-5)))
        xp = x0 + left + kp * cw + cw / 2
        out.append('<line x1="%g" y1="%d" x2="%g" y2="%d" stroke="black" stroke-dasharray="3,2"/>' % (xp, top - 6, xp, top + ch * len(rows)))
    out.append('<text x="10" y="%d" font-size="10">dt (s), factor sqrt 2; dashed: the paper\'s 5e-5 s. Green: stable, red: unstable (guard stop or kinetic energy grown), pale: below a stable dt (not run).</text>' % (height - 8))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--c0", type=float, nargs="+", default=[4.0, 8.0, 16.0])
    ap.add_argument("--mu", type=float, nargs="+", default=[0.01, 0.1, 1.0])
    ap.add_argument("--delta", type=float, nargs="+", default=[0.0, 0.1, 0.5])
    ap.add_argument("--tend", type=float, default=0.3)
    ap.add_argument("--svg", default=None)
    ap.add_argument("--bin", default=os.path.join(ROOT, "target/release/dmhs"))
    a = ap.parse_args()
    results = {}
    largest = {}
    with tempfile.TemporaryDirectory() as work:
        for c in a.c0:
            for m in a.mu:
                for d in a.delta:
                    largest[(c, m, d)] = None
                    for k in reversed(range(len(LADDER))):
                        ok, why = run(a.bin, c, m, d, LADDER[k], a.tend, work)
                        results[(c, m, d, k)] = ok
                        print("c0 %g mu %g delta %g dt %.4g: %s (%s)" % (c, m, d, LADDER[k], "stable" if ok else "unstable", why), flush=True)
                        if ok:
                            largest[(c, m, d)] = LADDER[k]
                            break
    print("\nlargest stable dt (s); 2 nu/c0^2 beside it")
    print("%6s %6s %s" % ("c0", "mu", " ".join("%12s" % ("delta %g" % d) for d in a.delta)) + "   2nu/c0^2")
    for c in a.c0:
        for m in a.mu:
            cells = " ".join("%12s" % ("%.3g" % largest[(c, m, d)] if largest[(c, m, d)] else "< %.3g" % LADDER[0]) for d in a.delta)
            print("%6g %6g %s   %.3g" % (c, m, cells, 2 * m / 1000.0 / c ** 2))
    if a.svg:
        svg(results, a.c0, a.mu, a.delta, a.svg)
        print("wrote", a.svg)


if __name__ == "__main__":
    sys.exit(main())
