#!/usr/bin/env python3
"""Write the bonded-clump data file of the gran_clumps_* decks (deterministic).

    python gen_clumps.py            # rewrites decks/gran_clumps.data

DMHS "point-like elemental particles bonded into clumps": each clump is a tetrahedron of four
spheres (diameter 0.9, density 1) joined by six harmonic bonds (rest length 1.0, the edges) and
twelve harmonic angles (60 degrees, every corner of every face), one molecule ID per clump; the
corners are jittered by up to 0.03 so that bonds and angles start with non-zero forces.
Two 3 x 3 blocks of clumps, randomly oriented, approach each other along x (vx = +4 and -4
plus a small seeded spread), offset in y and z so that the contacts are oblique; a few spheres of
the two blocks already overlap at step 0. The box is
periodic; the blocks sit across the y and z faces, so some clumps are split by the boundary
(image flags), and contact partners meet through periodic images.
"""

import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "decks", "gran_clumps.data")

DIAMETER = 0.9
DENSITY = 1.0
EDGE = 1.0
BOX = (16.0, 9.0, 9.0)
SPEED = 4.0
SEED = 20251124


def rotation(rng):
    """A random rotation matrix (from a random unit quaternion)."""
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    q = (math.sqrt(1 - u1) * math.sin(2 * math.pi * u2), math.sqrt(1 - u1) * math.cos(2 * math.pi * u2),
         math.sqrt(u1) * math.sin(2 * math.pi * u3), math.sqrt(u1) * math.cos(2 * math.pi * u3))
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def tetrahedron():
    """Corners of a regular tetrahedron with edge EDGE, centred at the origin."""
    s = EDGE / math.sqrt(8.0)
    return [[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]]


def main():
    rng = random.Random(SEED)
    atoms, vels, bonds, angles = [], [], [], []
    mol = 0
    spacing = 3.0
    for side, (x0, vx) in enumerate([(BOX[0] / 2 - 0.74, SPEED), (BOX[0] / 2 + 0.74, -SPEED)]):
        for iy in range(3):
            for iz in range(3):
                mol += 1
                # block 2 is shifted by a third of a spacing in y and z: oblique contacts;
                # the middle row sits on the periodic faces
                shift = 0.0 if side == 0 else spacing / 3
                c = [x0 + rng.uniform(-0.1, 0.1),
                     1.5 + iy * spacing + shift + rng.uniform(-0.1, 0.1),
                     1.5 + iz * spacing + shift + rng.uniform(-0.1, 0.1)]
                v = [vx + rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2)]
                r = rotation(rng)
                first = len(atoms) + 1
                for p in tetrahedron():
                    # a slightly deformed shape: bonds and angles start with forces
                    p = [p[k] + rng.uniform(-0.03, 0.03) for k in range(3)]
                    x = [c[k] + sum(r[k][m] * p[m] for m in range(3)) for k in range(3)]
                    atoms.append((mol, x))
                    vels.append(v)
                ids = list(range(first, first + 4))
                for a in range(4):
                    for b in range(a + 1, 4):
                        bonds.append((ids[a], ids[b]))
                # the 12 angles: each corner of each of the 4 faces
                for face in [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)]:
                    for k in range(3):
                        centre = face[k]
                        others = [face[m] for m in range(3) if m != k]
                        angles.append((ids[others[0]], ids[centre], ids[others[1]]))
    lo = [0.0, -BOX[1] / 2, -BOX[2] / 2]
    hi = [lo[0] + BOX[0], lo[1] + BOX[1], lo[2] + BOX[2]]
    lines = ["LAMMPS data file: bonded tetrahedral clumps (lammps-refs/gen_clumps.py)", "",
             f"{len(atoms)} atoms", "1 atom types", f"{len(bonds)} bonds", "1 bond types",
             f"{len(angles)} angles", "1 angle types", "",
             f"{lo[0]:.1f} {hi[0]:.1f} xlo xhi", f"{lo[1]:.1f} {hi[1]:.1f} ylo yhi",
             f"{lo[2]:.1f} {hi[2]:.1f} zlo zhi", "", "Atoms # hybrid sphere angle", ""]
    for k, (m, x) in enumerate(atoms):
        img = [0, 0, 0]
        for d in range(3):
            while x[d] < lo[d]:
                x[d] += hi[d] - lo[d]
                img[d] -= 1
            while x[d] >= hi[d]:
                x[d] -= hi[d] - lo[d]
                img[d] += 1
        lines.append(f"{k + 1} 1 {x[0]:.12f} {x[1]:.12f} {x[2]:.12f} {DIAMETER} {DENSITY} {m} {img[0]} {img[1]} {img[2]}")
    lines += ["", "Velocities", ""]
    for k, v in enumerate(vels):
        lines.append(f"{k + 1} {v[0]:.12f} {v[1]:.12f} {v[2]:.12f} 0 0 0")
    lines += ["", "Bonds", ""]
    for k, (a, b) in enumerate(bonds):
        lines.append(f"{k + 1} 1 {a} {b}")
    lines += ["", "Angles", ""]
    for k, (a, b, c) in enumerate(angles):
        lines.append(f"{k + 1} 1 {a} {b} {c}")
    with open(OUT, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
