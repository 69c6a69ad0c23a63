#!/usr/bin/env bash
# Rebuild the stored LAMMPS references: regenerate the chain data files, then run every deck
# decks/in.NAME through lammps_driver.py into refs/NAME/ (forces0.txt, final.txt, meta.json; the
# log.lammps beside them is not committed).
#
#     lammps-refs/regenerate.sh            # all decks
#     lammps-refs/regenerate.sh NAME ...   # some decks (NAME as in decks/in.NAME)
#     lammps-refs/regenerate.sh --chaos    # also measure each deck's round-off sensitivity
#     lammps-refs/regenerate.sh --shared   # only the shared decks (../shared/reference/lammps-decks)
#
# Python: $DMHS_LAMMPS_PYTHON, else <repo>/.venv-lammps/bin/python (scripts/setup-lammps.sh).
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
py=${DMHS_LAMMPS_PYTHON:-$here/../.venv-lammps/bin/python}
if [ ! -x "$py" ]; then
    echo "regenerate.sh: no LAMMPS python at $py; run scripts/setup-lammps.sh first" >&2
    exit 1
fi

chaos=0
shared_only=0
names=()
for arg in "$@"; do
    case "$arg" in
        --chaos) chaos=1 ;;
        --shared) shared_only=1 ;;
        *) names+=("$arg") ;;
    esac
done
if [ ${#names[@]} -eq 0 ] && [ "$shared_only" = 0 ]; then
    for deck in "$here"/decks/in.*; do names+=("${deck##*/in.}"); done
fi

"$py" "$here/gen_chains.py"
"$py" "$here/gen_sph.py"
"$py" "$here/gen_clumps.py"
"$py" "$here/gen_beds.py"
"$py" "$here/gen_coupling.py"
"$py" "$here/gen_bondchange.py"
"$py" "$here/gen_bpm.py"
for name in "${names[@]+"${names[@]}"}"; do
    echo "== $name"
    out="$here/refs/$name"
    rm -rf "$out"
    # the breaking BPM decks: their dump local of the broken bonds (tests/bpm_bonds.rs)
    extra=()
    case "$name" in
        bond_bpm_spring|bond_bpm_rotational) extra=(--var brkfile "$out/broken.txt") ;;
        # compute property/local: its dump local files (tests/property_local.rs)
        property_local_gran) extra=(--var pairsfile "$out/local.pairs" --var cutfile "$out/local.cut") ;;
        property_local_topo) extra=(--var bondsfile "$out/local.bonds" --var anglesfile "$out/local.angles" --var dihedralsfile "$out/local.dihedrals" --var pairsfile "$out/local.pairs") ;;
        # compute pair/local: its dump local files (tests/pair_local.rs)
        pair_local_chains|pair_local_hertz) extra=(--var pairsfile "$out/local.pairs") ;;
        pair_local_gran) extra=(--var pairsfile "$out/local.pairs" --var cutfile "$out/local.cut") ;;
    esac
    "$py" "$here/lammps_driver.py" "$here/decks/in.$name" --out "$out" "${extra[@]+"${extra[@]}"}"
    # bond/break, bond/create and thermostat decks: the thermo table of the last run (event counts
    # per step; the thermostats' f_ID energies, tests/thermostats.rs; the walls' f_ID, tests/walls.rs;
    # pe and pressure with fix_modify energy/virial, tests/fix_modify.rs; the rigid decks' pressure,
    # tests/rigid.rs; box and pressure of a
    # shrink-wrapped box, shrink_wrap_press; the reduced contacts arrays of wall/gran/region,
    # gran_region_contacts, tests/granular_region.rs)
    case "$name" in
        bond*|thermo_*|region_varshape|gran_region_varshape|rigid*|deposit_mol|walls_family|walls_region|walls_colloid|fix_modify_*|shrink_wrap_press|gran_region_contacts|gran_contact_atom|gran_jkr_walls|group_dynamic_property|aveforce_*|addforce_*|deform_*|msd_chunk_*|fix_momentum_rigid|adapt_*|npt_*|nph_*|property_local_*|pair_local_*) awk '/^ +Step/{p = 1; $1 = $1; t = "# " $0 "\n"; next} p && /^Loop time/{p = 0} p{t = t $0 "\n"} END{printf "%s", t}' \
                   "$out/log.lammps" > "$out/thermo.txt" ;;
        # the minimization's thermo table and its summary (tests/minimize.rs)
        min_*) awk '/^minimize /{m = 1} m && /^ +Step/{n++; if (n == 1) {p = 1; $1 = $1; print "# " $0; next}} p && /^Loop time/{p = 0} p; /^Minimization stats/{q = 1} q && /^ *$/{q = 0} q {print "## " $0}' \
                   "$out/log.lammps" > "$out/thermo.txt" ;;
        # the orientations at the end (tests/bpm.rs)
        bpm_sphere_nve) "$py" "$here/bpm_quat.py" "$here/decks/in.$name" "$out" ;;
        # the halt messages and the steps each run ended at (tests/fix_halt.rs)
        fix_halt*) grep -E '^(Fix halt|after )' "$out/log.lammps" > "$out/messages.txt" ;;
    esac
    if [ "$chaos" = 1 ]; then
        "$py" "$here/chaos_check.py" "$here/decks/in.$name"
    fi
done
du -ch "$here"/refs/*/{forces0.txt,final.txt,meta.json} | tail -n 1

# The shared reference decks (../shared/reference/lammps-decks), 500 steps, stored for every 25th
# atom only (the full tables would be several MB; the live test compares every atom).
shared_dir="$here/../../shared/reference/lammps-decks"
if [ $# -eq 0 ] || [ "$shared_only" = 1 ]; then
    for spec in "poiseuille2d:" "dambreak2d:" "dambreak2d:rhosum"; do
        deck=${spec%%:*}; variant=${spec#*:}
        name="shared_$deck${variant:+_$variant}"
        echo "== $name"
        out="$here/refs/$name"
        rm -rf "$out" && mkdir -p "$out"
        extra=()
        [ -n "$variant" ] && extra=(--var rhosum 1)
        tmp=$(mktemp -d)
        "$py" "$here/lammps_driver.py" "$shared_dir/in.$deck" --out "$tmp" --var nsteps 500 "${extra[@]}"
        "$py" - "$tmp" "$out" <<'PY'
import json, os, sys
src, dst = sys.argv[1], sys.argv[2]
for name in ("forces0.txt", "final.txt"):
    lines = open(os.path.join(src, name)).read().splitlines()
    keep = [lines[0]] + [l for l in lines[1:] if int(l.split()[0]) % 25 == 1]
    open(os.path.join(dst, name), "w").write("\n".join(keep) + "\n")
meta = json.load(open(os.path.join(src, "meta.json")))
meta["subsampled"] = "every 25th atom (ids 1, 26, 51, ...)"
json.dump(meta, open(os.path.join(dst, "meta.json"), "w"), indent=1)
PY
        rm -rf "$tmp"
    done
fi
