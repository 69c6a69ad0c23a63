#!/usr/bin/env python3
"""Data file of the Plinko cell sorter (Alexiadis 2015, Fig 14): a triangular array of fixed pins
and ring cells of 16 bonded particles placed at random (no overlap) above the pins, half of them
rigid (atom/angle type 1), half flexible (type 2). Python 3 standard library only.

    python3 gen_plinko.py [--length L] [--width W] [--cells N] [--rpin R] [--seed S] [-o FILE]

Lengths in metres. --length is the height of the pin array (the paper's chip is 1.5 mm long
and x0 = 0.45 mm wide; README.md says why the decks use shorter ones).
Atom types: 1 rigid-cell particle, 2 flexible-cell particle, 3 pin. One molecule per cell
(pins: molecule 0). Bonds (type 1) join ring neighbours; angles (type 1 rigid, 2 flexible) every
three consecutive ring particles.
"""
import argparse
import math
import random

NRING = 16          # particles per cell (paper)
R0 = 3.9e-6         # bond length (paper): ring radius R0 / (2 sin(pi/16)) = 10.0 um
PITCH = 30e-6       # distance between adjacent pins (paper), centre to centre
RHO = 1000.0        # particle density (paper)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--length", type=float, default=0.3e-3, help="height of the pin array (m)")
    ap.add_argument("--cells", type=int, default=24, help="number of cells (half rigid, half flexible)")
    ap.add_argument("--width", type=float, default=0.45e-3, help="chip width (m); the paper's x0 = 0.45 mm")
    ap.add_argument("--rpin", type=float, default=1.95e-6, help="pin radius (m); default: that of a cell particle")
    ap.add_argument("--seed", type=int, default=2015)
    ap.add_argument("-o", default="plinko.data")
    args = ap.parse_args()
    rnd = random.Random(args.seed)
    WIDTH = args.width

    rp = R0 / 2.0                                   # particle radius: neighbours touch
    rring = R0 / (2.0 * math.sin(math.pi / NRING))  # ring radius
    rcell = rring + rp                              # outer radius of a cell
    dy = PITCH * math.sqrt(3.0) / 2.0               # row spacing: every neighbour pin at PITCH
    floor_gap = 2.5 * rcell                         # room under the last row for collected cells
    nrows = int(args.length / dy) + 1
    ytop_pins = floor_gap + (nrows - 1) * dy
    # cells start in a band above the pins: as many rows of cells as needed, loosely packed
    per_row = int(WIDTH / (2.6 * rcell))
    bands = (args.cells + per_row - 1) // per_row + 1
    ycell0 = ytop_pins + args.rpin + 1.5 * rcell
    ytop = ycell0 + bands * 2.6 * rcell + rcell

    atoms = []   # (type, x, y, mol, diameter)
    # the chip is periodic in x (README.md): every row has WIDTH / PITCH pins, odd rows shifted
    # by half a pitch
    npins = round(WIDTH / PITCH)
    if abs(npins * PITCH - WIDTH) > 1e-9 * WIDTH:
        raise SystemExit("--width must be a multiple of the pin pitch 30 um")
    for k in range(nrows):
        y = floor_gap + k * dy
        for j in range(npins):
            atoms.append((3, (j + 0.5 * (k % 2 == 0)) * PITCH, y, 0, 2.0 * args.rpin))
    # random non-overlapping cell centres in the start band
    centres = []
    while len(centres) < args.cells:
        cx = rnd.uniform(1.05 * rcell, WIDTH - 1.05 * rcell)
        cy = rnd.uniform(ycell0, ytop - 1.05 * rcell)
        if all((cx - a) ** 2 + (cy - b) ** 2 > (2.1 * rcell) ** 2 for a, b in centres):
            centres.append((cx, cy))
    # in height order the kinds go rigid, flexible, flexible, rigid, ... so that both
    # populations start with about the same centre of mass (the paper: "y_C is approximately
    # the same for both types")
    centres.sort(key=lambda c: c[1])
    kinds = [1 + ((i + i // 2) % 2) for i in range(args.cells)]
    bonds, angles = [], []
    for c, ((cx, cy), kind) in enumerate(zip(centres, kinds)):
        first = len(atoms) + 1
        phase = rnd.uniform(0.0, 2.0 * math.pi / NRING)
        for j in range(NRING):
            t = phase + 2.0 * math.pi * j / NRING
            atoms.append((kind, cx + rring * math.cos(t), cy + rring * math.sin(t), c + 1, 2.0 * rp))
        for j in range(NRING):
            bonds.append((first + j, first + (j + 1) % NRING))
            angles.append((kind, first + j, first + (j + 1) % NRING, first + (j + 2) % NRING))

    mass = RHO * 4.0 / 3.0 * math.pi * rp ** 3
    with open(args.o, "w") as f:
        f.write(f"Plinko cell sorter (gen_plinko.py --length {args.length} --cells {args.cells} "
                f"--width {args.width} --rpin {args.rpin} --seed {args.seed})\n\n")
        f.write(f"{len(atoms)} atoms\n3 atom types\n{len(bonds)} bonds\n1 bond types\n")
        f.write(f"{len(angles)} angles\n2 angle types\n\n")
        f.write(f"0 {WIDTH!r} xlo xhi\n0 {ytop!r} ylo yhi\n{-rcell!r} {rcell!r} zlo zhi\n\n")
        # the deck sets the masses (`set type ... mass`); this is the paper's particle mass
        f.write(f"Masses\n\n1 {mass!r}\n2 {mass!r}\n3 {mass!r}\n\n")
        f.write("Atoms # hybrid sphere angle\n\n")
        for i, (t, x, y, mol, d) in enumerate(atoms, start=1):
            dens = mass / (math.pi / 6.0 * d ** 3)
            f.write(f"{i} {t} {x!r} {y!r} 0.0 {d!r} {dens!r} {mol}\n")
        f.write("\nBonds\n\n")
        for i, (a, b) in enumerate(bonds, start=1):
            f.write(f"{i} 1 {a} {b}\n")
        f.write("\nAngles\n\n")
        for i, (t, a, b, c) in enumerate(angles, start=1):
            f.write(f"{i} {t} {a} {b} {c}\n")


if __name__ == "__main__":
    main()
