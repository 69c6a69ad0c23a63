#!/usr/bin/env python3
"""Write the data files of the bpm_* and bond_bpm_rotational* decks (deterministic).

    python gen_bpm.py            # rewrites decks/bpm_blocks.data and decks/bpm_ball_plate.data

atom_style bpm/sphere (columns: id molecule type diameter density x y z): two blocks of 4 x 3 x 3
spheres (diameter 1, density 1, lattice spacing 1, jittered by up to 0.02), one molecule each,
joined by bonds between all pairs closer than 1.5 (type 1: the edges, about 1 long; type 2: the
face diagonals, about 1.41). Block 2
moves at vx = -1 towards block 1 with a seeded spread of velocities and spins (wx wy wz in the
Velocities section), offset in y and z, so the blocks meet obliquely. The box is non-periodic.

bpm_ball_plate.data: the same columns; a square plate (molecule 1) one fcc cell thick and a ball
(molecule 2) beside it, on an fcc lattice of density 1 (spacing 2^(2/3)), jittered by up to 0.1,
with bonds between all pairs of a molecule closer than 1.5 (type 1 in the plate, 2 in the ball),
at rest. The bonds come from the file so that LAMMPS' per-atom bond order is known (the order of
the file's Bonds lines).
"""

import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "decks", "bpm_blocks.data")
OUT_BALL_PLATE = os.path.join(HERE, "decks", "bpm_ball_plate.data")
SEED = 20261202
NX, NY, NZ = 4, 3, 3
CUT = 1.5


def main():
    rng = random.Random(SEED)
    atoms, vels, bonds = [], [], []
    for mol, (x0, y0, z0, vx) in enumerate([(-4.5, -1.0, -1.0, 0.0), (1.2, -0.6, -0.5, -1.0)], start=1):
        first = len(atoms)
        for i in range(NX):
            for j in range(NY):
                for k in range(NZ):
                    p = [x0 + i + rng.uniform(-0.02, 0.02), y0 + j + rng.uniform(-0.02, 0.02), z0 + k + rng.uniform(-0.02, 0.02)]
                    tag = len(atoms) + 1
                    atoms.append((tag, mol, 1, 1.0, 1.0, p))
                    v = [vx + rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)]
                    w = [rng.uniform(-0.5, 0.5) for _ in range(3)]
                    vels.append((tag, v, w))
        for a in range(first, len(atoms)):
            for b in range(a + 1, len(atoms)):
                d = math.dist(atoms[a][5], atoms[b][5])
                if d < CUT:
                    bonds.append((1 if d < 1.2 else 2, atoms[a][0], atoms[b][0]))
    lines = ["# bpm/sphere blocks for the bpm_* decks (gen_bpm.py)", "",
             f"{len(atoms)} atoms", "1 atom types", f"{len(bonds)} bonds", "2 bond types", "",
             "-8 8 xlo xhi", "-6 6 ylo yhi", "-6 6 zlo zhi", "", "Atoms # bpm/sphere", ""]
    for tag, mol, typ, d, rho, p in atoms:
        lines.append(f"{tag} {mol} {typ} {d} {rho} {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}")
    lines += ["", "Velocities", ""]
    for tag, v, w in vels:
        lines.append(f"{tag} " + " ".join(f"{c:.17g}" for c in v + w))
    lines += ["", "Bonds", ""]
    for n, (t, a, b) in enumerate(bonds, start=1):
        lines.append(f"{n} {t} {a} {b}")
    with open(OUT, "w") as f:
        f.write("\n".join(lines) + "\n")


def ball_plate():
    rng = random.Random(SEED + 1)
    a = 4.0 ** (1.0 / 3.0)
    basis = [(0.0, 0.0, 0.0), (0.5, 0.5, 0.0), (0.5, 0.0, 0.5), (0.0, 0.5, 0.5)]
    plate = lambda p: -0.5 <= p[0] <= 0.5 and -3 <= p[1] <= 3 and -3 <= p[2] <= 3
    ball = lambda p: (p[0] - 2.6) ** 2 + p[1] ** 2 + p[2] ** 2 <= 1.2 ** 2
    atoms, bonds = [], []
    for mol, inside in [(1, plate), (2, ball)]:
        first = len(atoms)
        for i in range(-2, 6):
            for j in range(-4, 5):
                for k in range(-4, 5):
                    for b in basis:
                        p = (i + b[0], j + b[1], k + b[2])
                        if inside(p):
                            q = [a * c + rng.uniform(-0.1, 0.1) for c in p]
                            atoms.append((len(atoms) + 1, mol, q))
        for m in range(first, len(atoms)):
            for n in range(m + 1, len(atoms)):
                if math.dist(atoms[m][2], atoms[n][2]) < CUT:
                    bonds.append((mol, atoms[m][0], atoms[n][0]))
    lines = ["# bpm/sphere ball and plate for the bond_bpm_rotational decks (gen_bpm.py)", "",
             f"{len(atoms)} atoms", "1 atom types", f"{len(bonds)} bonds", "2 bond types", "",
             "-10 13 xlo xhi", "-10 10 ylo yhi", "-10 10 zlo zhi", "", "Atoms # bpm/sphere", ""]
    for tag, mol, p in atoms:
        lines.append(f"{tag} {mol} 1 1.0 1.0 {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}")
    lines += ["", "Bonds", ""]
    for n, (t, i, j) in enumerate(bonds, start=1):
        lines.append(f"{n} {t} {i} {j}")
    with open(OUT_BALL_PLATE, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
    ball_plate()
