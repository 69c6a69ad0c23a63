#!/usr/bin/env python3
"""Write the data file of the bpm_* decks (deterministic).

    python gen_bpm.py            # rewrites decks/bpm_blocks.data

atom_style bpm/sphere (columns: id molecule type diameter density x y z): two blocks of 4 x 3 x 3
spheres (diameter 1, density 1, lattice spacing 1, jittered by up to 0.02), one molecule each,
joined by bonds between all pairs closer than 1.5 (type 1: the edges, about 1 long; type 2: the
face diagonals, about 1.41). Block 2
moves at vx = -1 towards block 1 with a seeded spread of velocities and spins (wx wy wz in the
Velocities section), offset in y and z, so the blocks meet obliquely. The box is non-periodic.
"""

import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "decks", "bpm_blocks.data")
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


if __name__ == "__main__":
    main()
