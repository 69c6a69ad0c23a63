#!/usr/bin/env python3
"""Write the SPH test configurations used by the sph_* reference decks (deterministic).

    python gen_sph.py       # rewrites decks/sph_{cluster,island}_{2d,3d}.data

Particles of two types on a jittered grid in a periodic box (cluster) or floating inside a fixed box
(island), with random
velocities, densities, internal energies and heat capacities, so that every term of every SPH
style is non-zero at step 0 (including pairs across the periodic faces for the clusters).
"""
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, dim, n_side, spacing, seed, periodic):
    rng = random.Random(seed)
    box = n_side * spacing
    atoms = []
    nz = n_side if dim == 3 else 1
    aid = 0
    for k in range(nz):
        for j in range(n_side):
            for i in range(n_side):
                aid += 1
                x = (i + 0.5) * spacing + rng.uniform(-0.25, 0.25) * spacing
                y = (j + 0.5) * spacing + rng.uniform(-0.25, 0.25) * spacing
                z = ((k + 0.5) * spacing + rng.uniform(-0.25, 0.25) * spacing) if dim == 3 else 0.0
                typ = 1 if rng.random() < 0.7 else 2
                rho = rng.uniform(0.95, 1.05)
                e = rng.uniform(0.5, 2.0)
                cv = rng.uniform(0.8, 1.2)
                v = [rng.gauss(0, 0.05) for _ in range(3)]
                if dim == 2:
                    v[2] = 0.0
                atoms.append((aid, typ, rho, e, cv, x, y, z, v))
    # masses give a mean density near rho0 = 1 (type 2 is 1.6 times heavier)
    m1 = spacing ** dim
    # non-periodic boxes keep a margin so that nothing leaves during the short runs
    lo, hi = (0.0, box) if periodic else (-0.5 * box, 1.5 * box)
    zlo, zhi = (lo, hi) if dim == 3 else (-0.5, 0.5)
    with open(os.path.join(HERE, "decks", name), "w") as f:
        f.write(f"SPH test cluster, {dim}D (gen_sph.py, seed {seed})\n\n")
        f.write(f"{len(atoms)} atoms\n2 atom types\n\n")
        f.write(f"{lo!r} {hi!r} xlo xhi\n{lo!r} {hi!r} ylo yhi\n{zlo!r} {zhi!r} zlo zhi\n\n")
        f.write(f"Masses\n\n1 {m1!r}\n2 {1.6 * m1!r}\n\nAtoms # sph\n\n")
        for (aid, typ, rho, e, cv, x, y, z, _) in atoms:
            f.write(f"{aid} {typ} {rho!r} {e!r} {cv!r} {x!r} {y!r} {z!r}\n")
        f.write("\nVelocities\n\n")
        for (aid, *_, v) in atoms:
            f.write(f"{aid} {v[0]!r} {v[1]!r} {v[2]!r}\n")


if __name__ == "__main__":
    write("sph_cluster_2d.data", 2, 14, 0.5, 2025, True)
    write("sph_cluster_3d.data", 3, 7, 0.5, 722, True)
    write("sph_island_2d.data", 2, 14, 0.5, 31, False)
    write("sph_island_3d.data", 3, 7, 0.5, 47, False)
