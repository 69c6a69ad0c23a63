#!/usr/bin/env python3
"""Writes the data files of the cubes-in-Poiseuille-flow scene (paper Fig 7), Python 3 standard
library only.

    python3 gen_cubes.py      # cubes_{A,B,C}.data (full), cubes_{A,B,C}_fast.data, cubes_C_land.data

A periodic channel (x) between two walls of three rows of fixed SPH particles; water on a square
grid of spacing dL = sqrt(m / rho) = 2.387e-3 m (m = 5.7e-3 kg per unit depth). Each cube is 7 x 7
elemental particles on a square lattice of spacing r0 = 2.3e-3 m (49 particles, the paper's Fig 5),
bonded to its lattice neighbours (84 bonds) with a 90 degree angle between every pair of
perpendicular bonds at a particle (144 angles); one molecule ID per cube.
Types: 1 water, 2 cube, 3 wall. Columns (atom_style hybrid sph sphere angle):
id type x y z rho esph cv diameter density molecule.
"""
import math

RHO_W = 1000.0
MW = 5.7e-3                  # water particle mass (kg per m of depth)
DL = math.sqrt(MW / RHO_W)    # 2.387e-3 m
R0 = DL                      # cube lattice spacing (m): the water spacing (paper 2.3e-3, see README)
NC = 7                       # particles per cube side
NWALL = 3
C0 = 8.0                     # Tait sound speed of in.cubes (m/s): sets the hydrostatic densities
G = 9.81


def hydrostatic_rho(rho0, y, y_surface):
    """Density whose Tait pressure B((rho/rho0)^7 - 1), B = c0^2 rho0 / 7, is the hydrostatic
    pressure of the water above y: the run starts at rest instead of settling (the settling
    transient shook the brittle cubes apart)."""
    p = max(0.0, RHO_W * G * (y_surface - y))
    return rho0 * (1.0 + p / (C0 * C0 * rho0 / 7.0)) ** (1.0 / 7.0)


def sphere_density(mass, diameter):
    # LAMMPS' per-atom mass of a sphere is 4/3 pi r^3 density (also in 2d): pick density so that
    # the per-atom mass equals the per-type mass the SPH styles use
    return mass / (4.0 / 3.0 * math.pi * (diameter / 2) ** 3)


def cube(cx, cy):
    return [(cx + (i - (NC - 1) / 2) * R0, cy + (j - (NC - 1) / 2) * R0) for j in range(NC) for i in range(NC)]


def build(name, nx, ny, fill, centres, rho_s):
    """nx x ny channel (in dL), water up to `fill` rows, cubes at `centres` (in m, moved to the
    nearest water site) of density rho_s."""
    lx, h = nx * DL, ny * DL
    centres = [((math.floor(x / DL) + 0.5) * DL, (math.floor(y / DL) + 0.5) * DL) for (x, y) in centres]
    solids = [p for c in centres for p in cube(*c)]

    def clear(x, y):
        # the cubes sit on the water lattice and replace its sites one for one: no void layer
        # around a cube (a gap of a fraction of dL adds displaced volume: spurious buoyancy)
        for (sx, sy) in solids:
            dx = (x - sx + lx / 2) % lx - lx / 2
            if math.hypot(dx, y - sy) < 0.5 * DL:
                return False
        return True

    water = [((i + 0.5) * DL, (j + 0.5) * DL) for i in range(nx) for j in range(fill)]
    water = [p for p in water if clear(*p)]
    ms = rho_s * R0 * R0
    atoms = [(x, y, 1, 0, RHO_W, DL, MW) for (x, y) in water]
    bonds, angles = [], []
    for k, c in enumerate(centres):
        first = len(atoms) + 1
        atoms += [(x, y, 2, k + 1, rho_s, R0, ms) for (x, y) in cube(*c)]
        idx = lambda i, j: first + j * NC + i
        for j in range(NC):
            for i in range(NC):
                if i + 1 < NC:
                    bonds.append((idx(i, j), idx(i + 1, j)))
                if j + 1 < NC:
                    bonds.append((idx(i, j), idx(i, j + 1)))
                # the 90-degree angles at (i, j): E-N, N-W, W-S, S-E where both neighbours exist
                nb = [(i + 1, j), (i, j + 1), (i - 1, j), (i, j - 1)]
                for a in range(4):
                    p, q = nb[a], nb[(a + 1) % 4]
                    if all(0 <= u < NC and 0 <= v < NC for (u, v) in (p, q)):
                        angles.append((idx(*p), idx(i, j), idx(*q)))
    for i in range(nx):
        x = (i + 0.5) * DL
        for k in range(NWALL):
            atoms.append((x, -(k + 0.5) * DL, 3, 0, RHO_W, DL, MW))
            atoms.append((x, h + (k + 0.5) * DL, 3, 0, RHO_W, DL, MW))
    ylo, yhi = -NWALL * DL - DL, h + NWALL * DL + DL
    y_surface = fill * DL
    atoms = [(x, y, t, mol, hydrostatic_rho(rho, y, y_surface), d, m) for (x, y, t, mol, rho, d, m) in atoms]
    with open(name, "w") as f:
        f.write(f"cubes in a periodic channel (gen_cubes.py): {len(water)} water, {len(centres)} cubes of density {rho_s}\n\n")
        f.write(f"{len(atoms)} atoms\n3 atom types\n{len(bonds)} bonds\n1 bond types\n{len(angles)} angles\n1 angle types\n\n")
        f.write(f"0.0 {lx!r} xlo xhi\n{ylo!r} {yhi!r} ylo yhi\n{-DL / 2!r} {DL / 2!r} zlo zhi\n\n")
        f.write(f"Masses\n\n1 {MW!r}\n2 {ms!r}\n3 {MW!r}\n\n")
        f.write("Atoms # hybrid\n\n")
        for n, (x, y, t, mol, rho, d, m) in enumerate(atoms, 1):
            f.write(f"{n} {t} {x!r} {y!r} 0.0 {rho!r} 0.0 1.0 {d!r} {sphere_density(m, d)!r} {mol}\n")
        f.write("\nBonds\n\n" + "".join(f"{k + 1} 1 {a} {b}\n" for k, (a, b) in enumerate(bonds)))
        f.write("\nAngles\n\n" + "".join(f"{k + 1} 1 {a} {b} {c}\n" for k, (a, b, c) in enumerate(angles)))
    print(f"{name}: {len(atoms)} atoms ({len(water)} water, {len(centres)} cubes), box {lx:.4f} x {h:.4f} m")


def grid(nx, ny, cols, rows, y0, y1, stagger=True):
    """Cube centres on a cols x rows pattern across the channel, rows between heights y0 and y1 (m)."""
    lx = nx * DL
    out = []
    for r in range(rows):
        y = y0 + (y1 - y0) * (r / (rows - 1) if rows > 1 else 0.5)
        for c in range(cols):
            x = (c + 0.5 + (0.5 if stagger and r % 2 else 0.0)) * lx / cols
            out.append((x, y))
    return out


def main():
    nx, ny = 80, 40
    h = ny * DL
    # A: neutrally buoyant cubes spread over the channel
    build("cubes_A.data", nx, ny, ny, grid(nx, ny, 4, 3, 0.2 * h, 0.8 * h), 1000.0)
    # B: light cubes (990) in a partly filled channel (free surface at 0.6 H): four start at the
    # surface (centre one spacing above the top water row), four (molecules 5-8) under it
    build("cubes_B.data", nx, ny, 24, grid(nx, ny, 4, 1, 0.6 * h, 0.6 * h) + grid(nx, ny, 4, 1, 0.35 * h, 0.35 * h), 990.0)
    # C: heavy brittle cubes (1500) starting in the upper half
    build("cubes_C.data", nx, ny, ny, grid(nx, ny, 4, 3, 0.45 * h, 0.85 * h), 1500.0)
    # fast variants: a quarter of the channel length with one column of cubes (a periodic cell
    # of the same pattern), fewer rows for B and C
    nxf = 20
    build("cubes_A_fast.data", nxf, ny, ny, grid(nxf, ny, 1, 3, 0.2 * h, 0.8 * h, False), 1000.0)
    build("cubes_B_fast.data", nxf, ny, 24, grid(nxf, ny, 1, 1, 0.6 * h, 0.6 * h, False), 990.0)
    build("cubes_C_fast.data", nxf, ny, ny, grid(nxf, ny, 1, 2, 0.13 * h, 0.42 * h, False), 1500.0)
    # C landing (fast, -var land 1): molecule 1 rests on the bottom wall (its lowest row one
    # spacing above the wall's top row, the DEM contact distance; no water under it), molecule 2
    # sits on it (adjacent lattice rows, no water film between them) and in.cubes launches it
    # downwards: the moment of impact, which the SPH water film between cubes never lets happen
    # within the full run (README)
    xc = 0.5 * nxf * DL
    build("cubes_C_land.data", nxf, ny, ny, [(xc, 3.2 * DL), (xc, 10.2 * DL)], 1500.0)


if __name__ == "__main__":
    main()
