#!/usr/bin/env python3
"""The three zones of Fig 9D against time, from the dumps of `-var zdump N`.

For each dump file PREFIX_zones.STEP.txt (id type x y melt-fraction) prints the time, the solid
fraction of the metal (melt fraction 0: e < e_sol), and, for the metal inside the mould
(0 < x < 0.3, y < 0.5), the count and the mean distance from the nearest mould face (x = 0,
x = 0.3, y = 0) of the solid (melt fraction 0), transition (between) and liquid (1) zones.
A crust at the faces and a liquid core read as d_solid < d_transition < d_liquid.
Python 3 standard library only: python3 zones.py casting_slow [dt]
"""
import glob
import re
import sys

prefix = sys.argv[1] if len(sys.argv) > 1 else "casting_slow"
dt = float(sys.argv[2]) if len(sys.argv) > 2 else 2.0e-4
files = sorted(glob.glob(f"{prefix}_zones.*.txt"), key=lambda f: int(re.findall(r"\.(\d+)\.txt$", f)[0]))
print("time   solid   in mould: n_sol n_tra n_liq   d_sol  d_tra  d_liq (m)")
for f in files:
    step = int(re.findall(r"\.(\d+)\.txt$", f)[0])
    lines = open(f).read().split("ITEM: ATOMS")[1].splitlines()[1:]
    rows = [[float(w) for w in ln.split()] for ln in lines if ln.strip()]
    nsol = sum(1 for r in rows if r[4] <= 0.0)
    zone = {"s": [], "t": [], "l": []}
    for _, _, x, y, m in rows:
        if 0.0 < x < 0.3 and y < 0.5:
            d = min(x, 0.3 - x, y)
            zone["s" if m <= 0.0 else "l" if m >= 1.0 else "t"].append(d)
    mean = lambda v: sum(v) / len(v) if v else float("nan")
    print(f"{step * dt:5.1f}  {nsol / len(rows):.3f}   {len(zone['s']):5d} {len(zone['t']):5d} {len(zone['l']):5d}   "
          f"{mean(zone['s']):.3f}  {mean(zone['t']):.3f}  {mean(zone['l']):.3f}")
