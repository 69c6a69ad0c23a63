#!/usr/bin/env python3
"""Writes the data files of the cell-in-a-channel scene (paper Fig 6), Python 3 standard library only.

    python3 gen_cells.py            # writes cell_constriction.data, cell_shear.data, cell_spike.data

Periodic channel (x) between two walls of three rows of fixed SPH particles. Fluid on a square
grid of spacing dL = 5e-6 m, 2048 fluid particles in every variant. The cell: a membrane of 48
particles on a circle (bond length r0 = 3.3e-6 m, so R = 48 r0 / (2 pi)) bonded as a ring with 48
angles (theta0 = 172.5 deg, the angle of the regular 48-gon), around a cytoplasm of 61 particles
on a hexagonal cluster of spacing dL (rings 0..4: 1+6+12+18+24). Types: 1 fluid, 2 cytoplasm,
3 membrane, 4 fixed wall/obstacle, 5 moving upper wall (shear variant only).
"""
import math

DL = 5.0e-6          # fluid spacing (m)
R0 = 3.3e-6          # membrane bond length (m)
NM, NFLUID = 48, 2048
NY = 20              # fluid rows: channel height H = NY dL = 100 um
NWALL = 3            # wall rows (the kernel support h = 11.8 um spans 2.4 dL)
RHO0 = 1000.0
RCELL = NM * R0 / (2 * math.pi)


def cytoplasm(cx, cy):
    pts = [(cx, cy)]
    for ring in range(1, 5):
        # walk the hexagon of the ring: 6 sides of `ring` steps
        corners = [(ring * DL * math.cos(math.pi / 3 * k), ring * DL * math.sin(math.pi / 3 * k)) for k in range(7)]
        for k in range(6):
            (ax, ay), (bx, by) = corners[k], corners[k + 1]
            for s in range(ring):
                t = s / ring
                pts.append((cx + ax + t * (bx - ax), cy + ay + t * (by - ay)))
    assert len(pts) == 61
    return pts


def build(name, nx, cell_x, obstacle, moving_top):
    """obstacle: list of (x, y) fixed particles inside the channel (besides the walls)."""
    lx, h = nx * DL, NY * DL
    cy = h / 2
    membrane = [(cell_x + RCELL * math.cos(2 * math.pi * k / NM), cy + RCELL * math.sin(2 * math.pi * k / NM)) for k in range(NM)]
    cyto = cytoplasm(cell_x, cy)
    walls = []
    for i in range(nx):
        x = (i + 0.5) * DL
        for k in range(NWALL):
            walls.append((x, -(k + 0.5) * DL, 4))
            walls.append((x, h + (k + 0.5) * DL, 5 if moving_top else 4))
    walls += [(x, y, 4) for (x, y) in obstacle]

    def clear(x, y):
        dx = (x - cell_x + lx / 2) % lx - lx / 2  # periodic distance to the cell centre
        if math.hypot(dx, y - cy) < RCELL + DL * 0.999:
            return False
        return all(math.hypot(((x - ox + lx / 2) % lx) - lx / 2, y - oy) > DL * 0.999 for (ox, oy) in obstacle)

    fluid = [((i + 0.5) * DL, (j + 0.5) * DL) for i in range(nx) for j in range(NY)]
    fluid = [p for p in fluid if clear(*p)]
    if len(fluid) < NFLUID:
        raise SystemExit(f"{name}: only {len(fluid)} fluid sites, lengthen the channel")
    # drop the surplus sites farthest downstream of the cell (a thin slit the fluid closes at once)
    print(f"{name}: {len(fluid)} fluid sites, {len(fluid) - NFLUID} dropped")
    fluid.sort(key=lambda p: ((p[0] - cell_x) % lx, p[1]))
    fluid = sorted(fluid[:NFLUID], key=lambda p: (p[0], p[1]))

    atoms = [(x, y, 1, 0) for (x, y) in fluid] + [(x, y, 2, 1) for (x, y) in cyto]
    first_mem = len(atoms) + 1
    atoms += [(x, y, 3, 1) for (x, y) in membrane]
    atoms += [(x, y, t, 0) for (x, y, t) in walls]
    bonds = [(first_mem + k, first_mem + (k + 1) % NM) for k in range(NM)]
    angles = [(first_mem + (k - 1) % NM, first_mem + k, first_mem + (k + 1) % NM) for k in range(NM)]
    ylo, yhi = -NWALL * DL - DL, h + NWALL * DL + DL
    with open(name, "w") as f:
        f.write(f"cell in a periodic channel (gen_cells.py): {len(fluid)} fluid, 61 cytoplasm, 48 membrane, {len(walls)} wall\n\n")
        f.write(f"{len(atoms)} atoms\n5 atom types\n{len(bonds)} bonds\n1 bond types\n{len(angles)} angles\n1 angle types\n\n")
        f.write(f"0.0 {lx!r} xlo xhi\n{ylo!r} {yhi!r} ylo yhi\n{-DL / 2!r} {DL / 2!r} zlo zhi\n\n")
        f.write("Masses\n\n" + "".join(f"{t} {RHO0 * DL * DL!r}\n" for t in range(1, 6)) + "\n")
        f.write("Atoms # hybrid\n\n")
        for i, (x, y, t, mol) in enumerate(atoms, 1):
            f.write(f"{i} {t} {x!r} {y!r} 0.0 {RHO0} 0.0 1.0 {mol}\n")
        f.write("\nBonds\n\n" + "".join(f"{k + 1} 1 {a} {b}\n" for k, (a, b) in enumerate(bonds)))
        f.write("\nAngles\n\n" + "".join(f"{k + 1} 1 {a} {b} {c}\n" for k, (a, b, c) in enumerate(angles)))
    print(f"{name}: {len(atoms)} atoms, box {lx:.3e} x {h:.3e} m, membrane ids {first_mem}..{first_mem + NM - 1}")


def main():
    h = NY * DL
    # B, C: a constriction across the channel, 3 columns thick, leaving 7 free rows in the middle
    nx = 110
    ox = 70 * DL
    cons = [(ox + (c + 0.5) * DL, (j + 0.5) * DL) for c in range(3) for j in range(NY) if j < 6 or j >= 13]
    build("cell_constriction.data", nx, ox - RCELL - 2.5 * DL, cons, False)
    # H: no obstacle, upper wall moving
    build("cell_shear.data", 108, 54 * DL, [], True)
    # I: a sharp spike on the channel axis pointing upstream: a tapered wedge of fixed particles
    spike = []
    tip = 70 * DL
    for c in range(8):
        half = c // 2  # rows on each side of the axis grow every two columns: a 14 degree wedge
        for j in range(-half, half + 1):
            spike.append((tip + c * DL, h / 2 + j * DL))
    build("cell_spike.data", 111, tip - RCELL - 3.5 * DL, spike, False)


if __name__ == "__main__":
    main()
