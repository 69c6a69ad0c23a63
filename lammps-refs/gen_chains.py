#!/usr/bin/env python3
"""Write the bead-spring chain data files used by the reference decks (deterministic).

    python gen_chains.py            # rewrites every file in PRESETS under decks/

Each chain is grown bead by bead from internal coordinates (bond length, bond angle, torsion)
close to the rest values of the decks' bonded styles, with a small seeded jitter so that the
step-0 bonded forces are non-zero but the stored energy stays small (low temperature, little
chaos). Chains are placed at seeded random spots and rejected when they overlap another bead
(non-bonded distance < MIN_DIST) or leave the allowed region. Types: beads 1, chain ends 2;
bond type 2 for a bond that touches a chain end, 1 otherwise; one angle and one dihedral type.
Torsions follow the IUPAC convention (trans = 180 degrees, LAMMPS' dihedral convention too).
"""

import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
MIN_DIST = 1.05

# name: atom style, box edge, periodic?, chains x beads, torsion centres (deg), jitter, seed
PRESETS = {
    # fixed walls (boundary f f f): helices near the quadratic dihedral's phi0 = 120 degrees
    "chains_walls.data": dict(style="molecular", box=13.0, periodic=False, nchains=10, nbeads=16,
                              torsions=[120.0], seed=20250722),
    # periodic box, chains cross the boundary (image flags): torsions at the minima of
    # dihedral harmonic K [1 + cos(3 phi)] (60, 180, 300 degrees), mixed at random
    "chains_periodic_full.data": dict(style="full", box=12.0, periodic=True, nchains=10,
                                      nbeads=16, torsions=[60.0, 180.0, -60.0], seed=7),
    "chains_periodic_angle.data": dict(style="angle", box=12.0, periodic=True, nchains=10,
                                       nbeads=16, torsions=[60.0, 180.0, -60.0], seed=11),
    "chains_periodic_bond.data": dict(style="bond", box=12.0, periodic=True, nchains=10,
                                      nbeads=16, torsions=[60.0, 180.0, -60.0], seed=13),
}

BOND0 = 0.97      # rest bond length used in the decks (bond type 1)
BOND0_END = 1.0   # bond type 2
ANGLE0 = 110.0    # rest bond angle (degrees)
MASSES = {1: 1.0, 2: 1.5}
MARGIN = 0.4      # walls: distance kept from every face


def sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    n = math.sqrt(sum(c * c for c in a))
    return [c / n for c in a]


def place(a, b, c, bond, angle, torsion):
    """Point d with |cd| = bond, angle bcd = angle, dihedral abcd = torsion (radians)."""
    bc = norm(sub(c, b))
    n = norm(cross(sub(b, a), bc))
    m = cross(n, bc)
    x = -bond * math.cos(angle)
    y = bond * math.sin(angle) * math.cos(torsion)
    z = bond * math.sin(angle) * math.sin(torsion)
    return [c[k] + x * bc[k] + y * m[k] + z * n[k] for k in range(3)]


def random_unit(rng):
    while True:
        v = [rng.uniform(-1, 1) for _ in range(3)]
        r = math.sqrt(sum(c * c for c in v))
        if 0.1 < r <= 1.0:
            return [c / r for c in v]


def grow_chain(rng, start, nbeads, torsions):
    bond = lambda i: (BOND0_END if i in (1, nbeads - 1) else BOND0) * (1 + rng.uniform(-0.02, 0.02))
    angle = lambda: math.radians(ANGLE0 + rng.uniform(-3.0, 3.0))
    u = random_unit(rng)
    p = [start, [start[k] + bond(1) * u[k] for k in range(3)]]
    # third bead: a dummy previous point off the first bond fixes the plane
    helper = [start[k] + w for k, w in enumerate(random_unit(rng))]
    p.append(place(helper, p[0], p[1], bond(2), angle(), rng.uniform(-math.pi, math.pi)))
    for i in range(3, nbeads):
        t = math.radians(rng.choice(torsions) + rng.uniform(-8.0, 8.0))
        p.append(place(p[i - 3], p[i - 2], p[i - 1], bond(i), angle(), t))
    return p


def distance(a, b, box, periodic):
    d = sub(a, b)
    if periodic:
        d = [c - box * round(c / box) for c in d]
    return math.sqrt(sum(c * c for c in d))


def fits(chain, beads, box, periodic):
    if not periodic and any(c < MARGIN or c > box - MARGIN for p in chain for c in p):
        return False
    for i, p in enumerate(chain):
        if any(distance(p, chain[j], box, periodic) < MIN_DIST for j in range(i - 3)):
            return False
        if any(distance(p, q, box, periodic) < MIN_DIST for q in beads):
            return False
    return True


def build(preset):
    rng = random.Random(preset["seed"])
    box, periodic = preset["box"], preset["periodic"]
    chains, beads = [], []
    while len(chains) < preset["nchains"]:
        for _attempt in range(10000):
            start = [rng.uniform(MARGIN, box - MARGIN) for _ in range(3)]
            chain = grow_chain(rng, start, preset["nbeads"], preset["torsions"])
            if fits(chain, beads, box, periodic):
                break
        else:
            raise SystemExit("could not place a chain: enlarge the box")
        chains.append(chain)
        beads += chain
    return chains


def topology(chains, nbeads, style):
    atoms, bonds, angles, dihedrals = [], [], [], []
    for c, chain in enumerate(chains):
        first = c * nbeads + 1
        ends = (first, first + nbeads - 1)
        for i, p in enumerate(chain):
            atoms.append((first + i, c + 1, 2 if first + i in ends else 1, p))
        ids = list(range(first, first + nbeads))
        for i in range(nbeads - 1):
            btype = 2 if ids[i] in ends or ids[i + 1] in ends else 1
            bonds.append((btype, ids[i], ids[i + 1]))
        if style != "bond":
            angles += [(1, ids[i], ids[i + 1], ids[i + 2]) for i in range(nbeads - 2)]
        if style in ("molecular", "full"):
            dihedrals += [(1,) + tuple(ids[i:i + 4]) for i in range(nbeads - 3)]
    return atoms, bonds, angles, dihedrals


def wrap(x, box):
    image = math.floor(x / box)
    return x - image * box, image


def write(path, name, preset):
    chains = build(preset)
    style, box = preset["style"], preset["box"]
    atoms, bonds, angles, dihedrals = topology(chains, preset["nbeads"], style)
    out = [f"LAMMPS data file: {len(chains)} bead-spring chains, written by gen_chains.py ({name})",
           "", f"{len(atoms)} atoms", f"{len(bonds)} bonds"]
    if style != "bond":
        out.append(f"{len(angles)} angles")
    if style in ("molecular", "full"):
        out.append(f"{len(dihedrals)} dihedrals")
    out += ["", "2 atom types", "2 bond types"]
    if style != "bond":
        out.append("1 angle types")
    if style in ("molecular", "full"):
        out.append("1 dihedral types")
    out += ["", f"0 {box} xlo xhi", f"0 {box} ylo yhi", f"0 {box} zlo zhi", "", "Masses", ""]
    out += [f"{t} {m}" for t, m in MASSES.items()]
    out += ["", f"Atoms # {style}", ""]
    for aid, mol, atype, p in atoms:
        if preset["periodic"]:
            coords = [wrap(c, box) for c in p]
        else:
            coords = [(c, 0) for c in p]
        xyz = " ".join("%.12f" % c for c, _ in coords)
        img = " ".join(str(i) for _, i in coords)
        charge = " 0.0" if style == "full" else ""
        out.append(f"{aid} {mol} {atype}{charge} {xyz} {img}")
    sections = [("Bonds", bonds), ("Angles", angles), ("Dihedrals", dihedrals)]
    for title, rows in sections:
        if rows:
            out += ["", title, ""]
            out += [" ".join(str(v) for v in (k + 1,) + row) for k, row in enumerate(rows)]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    for name, preset in PRESETS.items():
        write(os.path.join(HERE, "decks", name), name, preset)
        print(f"wrote decks/{name}")


if __name__ == "__main__":
    main()
