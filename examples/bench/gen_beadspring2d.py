#!/usr/bin/env python3
"""Write beadspring2d.data: a 2D bead-spring melt start, 500 chains of 20 beads (10,000 atoms).

Chains lie along x on a rectangular grid (bond 0.97, rows 1.05 apart), alternating direction row
by row, in a periodic box; velocities come from the deck. Deterministic (no random numbers).
    python3 gen_beadspring2d.py      # rewrites beadspring2d.data next to this file
"""
import os

NCH_X, NROWS, NBEADS = 10, 50, 20      # 10 chains per row, 50 rows -> 500 chains
BOND, ROW = 0.97, 1.05
LX, LY = NCH_X * NBEADS * BOND, NROWS * ROW


def main():
    atoms, bonds, angles = [], [], []
    aid = 0
    mol = 0
    for r in range(NROWS):
        for c in range(NCH_X):
            mol += 1
            first = aid + 1
            for b in range(NBEADS):
                aid += 1
                x = (c * NBEADS + b) * BOND + 0.5 * BOND
                y = r * ROW + 0.5 * ROW
                atoms.append((aid, mol, 1, x, y, 0.0))
                if b > 0:
                    bonds.append((len(bonds) + 1, 1, aid - 1, aid))
                if b > 1:
                    angles.append((len(angles) + 1, 1, aid - 2, aid - 1, aid))
            assert aid == first + NBEADS - 1
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "beadspring2d.data")
    with open(path, "w") as f:
        f.write("2D bead-spring melt start (gen_beadspring2d.py)\n\n")
        f.write(f"{len(atoms)} atoms\n1 atom types\n{len(bonds)} bonds\n1 bond types\n{len(angles)} angles\n1 angle types\n\n")
        f.write(f"0 {LX!r} xlo xhi\n0 {LY!r} ylo yhi\n-0.5 0.5 zlo zhi\n\nMasses\n\n1 1.0\n\nAtoms # angle\n\n")
        for a in atoms:
            f.write("%d %d %d %r %r %r\n" % a)
        f.write("\nBonds\n\n")
        for b in bonds:
            f.write("%d %d %d %d\n" % b)
        f.write("\nAngles\n\n")
        for a in angles:
            f.write("%d %d %d %d %d\n" % a)


if __name__ == "__main__":
    main()
