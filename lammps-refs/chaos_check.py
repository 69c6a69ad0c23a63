#!/usr/bin/env python3
"""Measure how far round-off moves a deck's reference: run it in LAMMPS with changed summation
orders and compare with the plain run.

    python chaos_check.py DECK [--var NAME VALUE ...] [--keep DIR]

Variants (each a full driver run): `newton off` (ghost forces summed on both sides),
`atom_modify sort 0 0.0` (no spatial sort: other neighbour-list order), `atom_modify sort 10 0.6`
(other sort), and --whole (the deck unsplit, no `run 0` inserted: must match the base bit for bit).
Prints, per variant, max |dF0| / max |F0| and max |dxu| / max box length, and max |dv| / max |v|.
"""

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
VARIANTS = [
    ("newton_off", ["--pre", "newton off"]),
    ("sort_off", ["--pre", "atom_modify sort 0 0.0"]),
    ("sort_other", ["--pre", "atom_modify sort 10 0.6"]),
    ("whole", ["--whole"]),
]


def load(path):
    return np.loadtxt(path, ndmin=2)


def run(deck, out, extra, var):
    cmd = [sys.executable, os.path.join(HERE, "lammps_driver.py"), deck, "--out", out] + extra
    for name, value in var:
        cmd += ["--var", name, value]
    subprocess.run(cmd, check=True)


def box_length(out):
    import json
    with open(os.path.join(out, "meta.json")) as f:
        b = json.load(f)["box"]
    return max(h - l for h, l in zip(b["hi"], b["lo"]))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("deck")
    p.add_argument("--var", nargs=2, action="append", default=[])
    p.add_argument("--keep", help="write the runs under this folder instead of a temporary one")
    a = p.parse_args()
    root = a.keep or tempfile.mkdtemp(prefix="chaos-")
    base = os.path.join(root, "base")
    run(a.deck, base, [], a.var)
    f0, fin = load(os.path.join(base, "forces0.txt")), load(os.path.join(base, "final.txt"))
    # a deck whose atoms are all inserted during the run (fix pour) has no step-0 forces
    fscale = np.abs(f0[:, 2:5]).max(initial=0.0)
    vscale = np.abs(fin[:, 5:8]).max()
    L = box_length(base)
    print(f"{os.path.basename(a.deck)}: natoms {len(fin)}, max|F0| {fscale:.3g}, "
          f"box {L:.6g}, max|v| {vscale:.3g}")
    worst = 0.0
    for name, extra in VARIANTS:
        out = os.path.join(root, name)
        run(a.deck, out, extra, a.var)
        other = load(os.path.join(out, "final.txt"))
        dx = np.abs(other[:, 2:5] - fin[:, 2:5]).max() / L
        dv = np.abs(other[:, 5:8] - fin[:, 5:8]).max() / vscale
        line = f"  {name:11s} dxu/L {dx:.2e}  dv/vmax {dv:.2e}"
        if name != "whole":
            df = np.abs(load(os.path.join(out, "forces0.txt"))[:, 2:5] - f0[:, 2:5]).max(initial=0.0) / (fscale or 1.0)
            line += f"  dF0/Fmax {df:.2e}"
            worst = max(worst, dx)
        print(line)
    print(f"  worst dxu/L {worst:.2e}")


if __name__ == "__main__":
    main()
