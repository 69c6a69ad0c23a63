#!/usr/bin/env python3
"""Write granular bed data files (deterministic): spheres on a jittered simple cubic lattice with
small random velocities, in a box periodic in x and y above a floor at z = 0 (or a periodic cube).
They serve decks that must also run in LIGGGHTS, which has no `velocity create` (the random
start is in the file).

    python gen_beds.py            # rewrites every file in PRESETS

Atom style sphere (LIGGGHTS: granular): `id type diameter density x y z`; type 1 diameter D1,
type 2 diameter D2 (every other atom in creation order), density 1. Velocities `vx vy vz 0 0 0`.
"""

import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

# path: lattice counts (x, y, z), spacing, diameters, jitter, speed, seed
PRESETS = {
    os.path.join(HERE, "decks", "gran_bed.data"): dict(n=(10, 10, 10), a=1.05, d=(1.0, 0.9), jitter=0.02, speed=0.3, seed=20251124),
    os.path.join(HERE, "..", "examples", "bench", "granular_bed.data"): dict(n=(25, 25, 16), a=1.05, d=(1.0, 0.8), jitter=0.02, speed=1.0, seed=87287),
}


def write(path, n, a, d, jitter, speed, seed, cube=False):
    rng = random.Random(seed)
    nx, ny, nz = n
    lx, ly, lz = nx * a, ny * a, (1.0 if cube else 2.5) * nz * a
    atoms, vels = [], []
    k = 0
    for iz in range(nz):
        for iy in range(ny):
            for ix in range(nx):
                k += 1
                typ = 1 if k % 2 == 1 else 2
                x = (ix + 0.5) * a + rng.uniform(-jitter, jitter)
                y = (iy + 0.5) * a + rng.uniform(-jitter, jitter)
                z = (iz + 0.5) * a + (rng.uniform(-jitter, jitter) if cube else rng.uniform(0.0, jitter))
                atoms.append(f"{k} {typ} {d[typ - 1]} 1.0 {x:.7f} {y:.7f} {z:.7f}")
                vels.append(f"{k} {rng.uniform(-speed, speed):.7f} {rng.uniform(-speed, speed):.7f} {rng.uniform(-speed, speed):.7f} 0 0 0")
    lines = [f"LAMMPS data file: granular bed, {k} spheres (lammps-refs/gen_beds.py)", "",
             f"{k} atoms", "2 atom types", "",
             f"0.0 {lx:.10g} xlo xhi", f"0.0 {ly:.10g} ylo yhi", f"0.0 {lz:.10g} zlo zhi", "",
             "Atoms # sphere", ""] + atoms + ["", "Velocities", ""] + vels
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    for path, p in PRESETS.items():
        write(os.path.normpath(path), **p)


if __name__ == "__main__":
    main()
