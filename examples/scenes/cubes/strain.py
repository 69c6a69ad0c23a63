"""Lattice vibration and water noise of a cubes run (README, "The time step").

    dmhs run in.cubes -var case C -var dumpn 32000   # writes cubes_C.dump
    python3 strain.py cubes_C.data cubes_C.dump

Per dump frame: the largest and smallest bond strain (r - r0)/r0 of all cube bonds in the data
file (broken bonds included: a broken bond shows as a large strain), the largest kinetic energy of
a cube relative to its own centre of mass (its lattice vibration, J per m of depth), and the
kinetic energy of the water relative to the mean velocity of its layer (bins one spacing high:
the acoustic noise; the mean shear flow is not counted), and Fig 7C's two numbers (README,
"Measured against the paper"): the cubes deposited (centre below y = 3.5 r0 + 1.5 dL, where a cube
touching the wall has its centre at 3.5 r0: on the bottom, with at most the one water layer that
stays under a cube; tests/scene_cubes.rs uses the same height) and the
cubes fractured (a bond of the data file longer than 1.001 r0, the breakage length of case C).
Python 3 standard library only.
"""
import math
import sys

R0 = 0.0023874672772626646  # bond length = water spacing (gen_cubes.py)
DEPOSITED = 5.0 * R0  # y of a deposited cube's centre: 3.5 r0 touching the wall (top row at -dL/2) + 1.5 dL
RMAXF = 1.001  # breakage length / r0 of case C


def read_data(name):
    bonds, masses, lx, sec = [], {}, None, None
    for line in open(name):
        s = line.strip()
        if s in ("Masses", "Atoms # hybrid", "Bonds", "Angles"):
            sec = s
            continue
        w = s.split()
        if not w:
            continue
        if "xlo" in s:
            lx = float(w[1]) - float(w[0])
        elif sec == "Bonds":
            bonds.append((int(w[2]), int(w[3])))
        elif sec == "Masses":
            masses[int(w[0])] = float(w[1])
    return bonds, masses, lx


def frames(name):
    """(step, {id: (mol, type, x, y, vx, vy)}) per snapshot of a `dump custom` with those columns."""
    f = open(name)
    while f.readline():
        step = int(f.readline())
        f.readline()
        n = int(f.readline())
        for _ in range(5):
            f.readline()
        atoms = {}
        for _ in range(n):
            w = f.readline().split()
            atoms[int(w[0])] = (int(w[1]), int(w[2])) + tuple(float(x) for x in w[3:7])
        yield step, atoms


def internal_ke(m, vs):
    """Kinetic energy of particles of mass m with velocities vs relative to their mean velocity."""
    cx = sum(v[0] for v in vs) / len(vs)
    cy = sum(v[1] for v in vs) / len(vs)
    return 0.5 * m * sum((v[0] - cx) ** 2 + (v[1] - cy) ** 2 for v in vs)


def main():
    bonds, masses, lx = read_data(sys.argv[1])
    print("step max_strain min_strain max_cube_internal_KE water_noise_KE deposited fractured cubes")
    for step, at in frames(sys.argv[2]):
        strains, broken = [], set()
        for a, b in bonds:
            dx = at[a][2] - at[b][2]
            dx -= lx * round(dx / lx)
            strains.append((math.hypot(dx, at[a][3] - at[b][3]) - R0) / R0)
            if strains[-1] > RMAXF - 1.0:
                broken.add(at[a][0])
        cubes, heights, layers = {}, {}, {}
        for mol, typ, x, y, vx, vy in at.values():
            if typ == 2:
                cubes.setdefault(mol, []).append((vx, vy))
                heights.setdefault(mol, []).append(y)
            elif typ == 1:
                layers.setdefault(math.floor(y / R0), []).append((vx, vy))
        kc = max(internal_ke(masses[2], vs) for vs in cubes.values())
        kw = sum(internal_ke(masses[1], vs) for vs in layers.values())
        deposited = sum(1 for ys in heights.values() if sum(ys) / len(ys) < DEPOSITED)
        print(f"{step} {max(strains):.3e} {min(strains):.3e} {kc:.2e} {kw:.2e} {deposited} {len(broken)} {len(cubes)}")


if __name__ == "__main__":
    main()
