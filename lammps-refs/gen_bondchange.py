#!/usr/bin/env python3
"""Write the data files of the bond/break and bond/create reference decks (deterministic).

    python gen_bondchange.py   # rewrites decks/capsule_2d.data, decks/bondcreate_2d.data

capsule_2d.data (atom_style angle, 2D): a ring of 20 beads (radius 3, jittered by up to 0.03),
consecutive beads bonded (type 1, rest length = chord) with an angle at every bead; the left
half is type 1, the right half type 2 (the deck pulls the halves apart with fix addforce).
bondcreate_2d.data (atom_style angle, 2D): a bonded chain of 6 type-1 beads along x (bond type 1,
angles type 1) and 8 type-2 beads above it drifting down onto it; headers reserve room for
the bonds, angles and special neighbours that fix bond/create adds.
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(x):
    return repr(float(x))


def write(name, title, ntypes, box, atoms, vels, bonds, angles, extra):
    lines = [title, "", f"{len(atoms)} atoms", f"{ntypes} atom types", f"{len(bonds)} bonds", "2 bond types",
             f"{len(angles)} angles", "1 angle types"] + extra + ["",
             f"{fmt(-box)} {fmt(box)} xlo xhi", f"{fmt(-box)} {fmt(box)} ylo yhi", "-0.5 0.5 zlo zhi", "",
             "Masses", ""] + [f"{t + 1} 1.0" for t in range(ntypes)] + ["", "Atoms # angle", ""]
    lines += [f"{k + 1} {mol} {t} {fmt(x)} {fmt(y)} 0.0" for k, (mol, t, x, y) in enumerate(atoms)]
    lines += ["", "Velocities", ""] + [f"{k + 1} {fmt(v[0])} {fmt(v[1])} 0.0" for k, v in enumerate(vels)]
    lines += ["", "Bonds", ""] + [f"{k + 1} {t} {a} {b}" for k, (t, a, b) in enumerate(bonds)]
    lines += ["", "Angles", ""] + [f"{k + 1} 1 {a} {b} {c}" for k, (a, b, c) in enumerate(angles)]
    with open(os.path.join(HERE, "decks", name), "w") as f:
        f.write("\n".join(lines) + "\n")


def capsule():
    rng = random.Random(7)
    n, r = 20, 3.0
    atoms, vels = [], []
    for k in range(n):
        a = 2 * math.pi * (k + 0.5) / n
        x, y = r * math.cos(a) + rng.uniform(-0.03, 0.03), r * math.sin(a) + rng.uniform(-0.03, 0.03)
        atoms.append((1, 2 if x > 0 else 1, x, y))
        vels.append((rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02)))
    bonds = [(1, k + 1, (k + 1) % n + 1) for k in range(n)]
    angles = [((k - 1) % n + 1, k + 1, (k + 1) % n + 1) for k in range(n)]
    write("capsule_2d.data", "Bonded ring pulled apart (gen_bondchange.py)", 2, 8.0, atoms, vels, bonds, angles, [])


def bondcreate():
    rng = random.Random(11)
    atoms, vels, bonds, angles = [], [], [], []
    for k in range(6):
        atoms.append((1, 1, -2.5 + k + rng.uniform(-0.02, 0.02), rng.uniform(-0.02, 0.02)))
        vels.append((0.0, 0.0))
    bonds = [(1, k + 1, k + 2) for k in range(5)]
    angles = [(k + 1, k + 2, k + 3) for k in range(4)]
    for k in range(8):
        atoms.append((2 + k, 2, -3.2 + 0.85 * k + rng.uniform(-0.05, 0.05), 1.6 + rng.uniform(-0.1, 0.3)))
        vels.append((rng.uniform(-0.1, 0.1), -0.6 + rng.uniform(-0.1, 0.1)))
    extra = ["4 extra bond per atom", "6 extra angle per atom", "12 extra special per atom"]
    write("bondcreate_2d.data", "Chain and free beads for fix bond/create (gen_bondchange.py)", 4, 6.0, atoms, vels,
          bonds, angles, extra)


if __name__ == "__main__":
    capsule()
    bondcreate()
