#!/usr/bin/env python3
"""Write the data files of the multi-hybrid coupling decks (deterministic).

    python gen_coupling.py     # rewrites decks/coupling_2d.data, decks/couette_wall_2d.data
                               # (and examples/coupling/couette_wall_2d.data)

coupling_2d.data (atom_style hybrid sph sphere angle, 2D, periodic 10 x 10):
  type 1: SPH fluid on a jittered 0.5 grid, random densities, random velocities away from the
          periodic faces;
  type 2: a bonded ring of 10 elemental particles (molecule 1; harmonic bonds between
          neighbours, harmonic angles at every particle), moving +x;
  type 3: a bonded 2 x 3 block (molecule 2; bonds along rows and columns, angles along rows),
          moving -x into the ring: DEM contact between the two solids after about 100 steps.
  Fluid sites closer than 0.6 to a solid particle are left empty.
couette_wall_2d.data (same atom style, periodic in x, fixed in y):
  type 1: fluid, 10 x 10 at spacing 0.1 between two walls;
  type 2: bottom wall, type 3: top wall, each three rows of elemental particles bonded to their
          row and column neighbours (one molecule per wall).
"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(x):
    return repr(float(x))


def write(path, title, box, ntypes, masses, atoms, vels, bonds, angles):
    """atoms: (type, x, y, rho, esph, cv, diameter, density, molecule)."""
    lines = [title, "", f"{len(atoms)} atoms", f"{ntypes} atom types", f"{len(bonds)} bonds", "1 bond types",
             f"{len(angles)} angles", "1 angle types", "",
             f"{fmt(box[0][0])} {fmt(box[0][1])} xlo xhi", f"{fmt(box[1][0])} {fmt(box[1][1])} ylo yhi",
             "-0.5 0.5 zlo zhi", "", "Masses", ""]
    lines += [f"{t + 1} {fmt(m)}" for t, m in enumerate(masses)]
    lines += ["", "Atoms # hybrid sph sphere angle", ""]
    for k, (t, x, y, rho, e, cv, d, dens, mol) in enumerate(atoms):
        lines.append(f"{k + 1} {t} {fmt(x)} {fmt(y)} 0.0 {fmt(rho)} {fmt(e)} {fmt(cv)} {fmt(d)} {fmt(dens)} {mol}")
    lines += ["", "Velocities", ""]
    lines += [f"{k + 1} {fmt(v[0])} {fmt(v[1])} 0.0 0.0 0.0 0.0" for k, v in enumerate(vels)]
    if bonds:
        lines += ["", "Bonds", ""]
        lines += [f"{k + 1} 1 {a} {b}" for k, (a, b) in enumerate(bonds)]
    if angles:
        lines += ["", "Angles", ""]
        lines += [f"{k + 1} 1 {a} {b} {c}" for k, (a, b, c) in enumerate(angles)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def density_for(mass, d):
    """Sphere density giving per-atom mass `mass` (LAMMPS: m = 4/3 pi r^3 density, also in 2D)."""
    return mass / (4.0 / 3.0 * math.pi * (0.5 * d) ** 3)


def coupling():
    rng = random.Random(20251124)
    L, dx = 10.0, 0.5
    mfluid, msolid, dsolid = 0.25, 0.3, 0.7
    solids = []  # (type, x, y, mol)
    ring_c, ring_r, nring = (3.6, 5.0), 1.2, 10
    for k in range(nring):
        a = 2 * math.pi * k / nring
        solids.append((2, ring_c[0] + ring_r * math.cos(a), ring_c[1] + ring_r * math.sin(a), 1))
    for r in range(3):
        for c in range(2):
            solids.append((3, 5.55 + 0.7 * c, 4.6 + 0.7 * r + 0.15, 2))
    atoms, vels = [], []
    for j in range(int(L / dx)):
        for i in range(int(L / dx)):
            x = (i + 0.5) * dx + rng.uniform(-0.1, 0.1) * dx
            y = (j + 0.5) * dx + rng.uniform(-0.1, 0.1) * dx
            if min(math.hypot(x - s[1], y - s[2]) for s in solids) < 0.6:
                continue
            atoms.append((1, x, y, rng.uniform(0.98, 1.02), rng.uniform(0.5, 1.5), 1.0, dx, density_for(mfluid, dx), 0))
            # moving fluid only away from the periodic faces (further than h + skin): at step 0
            # dmhs and LAMMPS (newton on) differ for moving pairs across a face (docs/commands.md)
            inner = min(x, y, L - x, L - y) > 1.4
            vels.append((rng.gauss(0, 0.05), rng.gauss(0, 0.05)) if inner else (0.0, 0.0))
    first = len(atoms) + 1
    for (t, x, y, mol) in solids:
        atoms.append((t, x, y, 1.0, 1.0, 1.0, dsolid, density_for(msolid, dsolid), mol))
        vx = 0.5 if t == 2 else -0.5
        vels.append((vx + rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05)))
    ring = [first + k for k in range(nring)]
    bonds = [(ring[k], ring[(k + 1) % nring]) for k in range(nring)]
    angles = [(ring[(k - 1) % nring], ring[k], ring[(k + 1) % nring]) for k in range(nring)]
    blk = [first + nring + k for k in range(6)]  # row r, column c -> blk[2r + c]
    bonds += [(blk[2 * r], blk[2 * r + 1]) for r in range(3)]
    bonds += [(blk[2 * r + c], blk[2 * r + 2 + c]) for r in range(2) for c in range(2)]
    angles += [(blk[c], blk[2 + c], blk[4 + c]) for c in range(2)]
    write(os.path.join(HERE, "decks", "coupling_2d.data"), "DMHS coupling test: SPH fluid, bonded ring, bonded block (gen_coupling.py)",
          ((0.0, L), (0.0, L)), 3, [mfluid, msolid, msolid], atoms, vels, bonds, angles)


def couette():
    dx, nx, nfluid, nwall = 0.1, 10, 10, 3
    m = dx * dx  # rho0 = 1
    atoms, vels, bonds, angles = [], [], [], []
    # rows: bottom wall y = -(nwall-1)dx .. 0, fluid y = dx .. nfluid dx, top wall above
    def wall(typ, ys, mol):
        ids = {}
        for r, y in enumerate(ys):
            for i in range(nx):
                atoms.append((typ, (i + 0.5) * dx, y, 1.0, 1.0, 1.0, dx, density_for(m, dx), mol))
                vels.append((0.0, 0.0))
                ids[(r, i)] = len(atoms)
        for r in range(len(ys)):
            for i in range(nx):
                bonds.append((ids[(r, i)], ids[(r, (i + 1) % nx)]))
                if r + 1 < len(ys):
                    bonds.append((ids[(r, i)], ids[(r + 1, i)]))
    wall(2, [-k * dx for k in reversed(range(nwall))], 1)
    for j in range(nfluid):
        for i in range(nx):
            atoms.append((1, (i + 0.5) * dx, (j + 1) * dx, 1.0, 1.0, 1.0, dx, density_for(m, dx), 0))
            vels.append((0.0, 0.0))
    wall(3, [(nfluid + 1 + k) * dx for k in range(nwall)], 2)
    lo, hi = -nwall * dx, (nfluid + nwall + 1) * dx
    for path in (os.path.join(HERE, "decks", "couette_wall_2d.data"),
                 os.path.join(HERE, "..", "examples", "coupling", "couette_wall_2d.data")):
        write(path, "Couette channel between bonded walls (gen_coupling.py)", ((0.0, nx * dx), (lo, hi)), 3,
              [m, m, m], atoms, vels, bonds, [])


if __name__ == "__main__":
    coupling()
    couette()
