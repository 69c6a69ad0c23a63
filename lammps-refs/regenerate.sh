#!/usr/bin/env bash
# Rebuild the stored LAMMPS references: regenerate the chain data files, then run every deck
# decks/in.NAME through lammps_driver.py into refs/NAME/ (forces0.txt, final.txt, meta.json; the
# log.lammps beside them is not committed).
#
#     lammps-refs/regenerate.sh            # all decks
#     lammps-refs/regenerate.sh NAME ...   # some decks (NAME as in decks/in.NAME)
#     lammps-refs/regenerate.sh --chaos    # also measure each deck's round-off sensitivity
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
names=()
for arg in "$@"; do
    case "$arg" in
        --chaos) chaos=1 ;;
        *) names+=("$arg") ;;
    esac
done
if [ ${#names[@]} -eq 0 ]; then
    for deck in "$here"/decks/in.*; do names+=("${deck##*/in.}"); done
fi

"$py" "$here/gen_chains.py"
"$py" "$here/gen_clumps.py"
"$py" "$here/gen_beds.py"
for name in "${names[@]}"; do
    echo "== $name"
    out="$here/refs/$name"
    rm -rf "$out"
    "$py" "$here/lammps_driver.py" "$here/decks/in.$name" --out "$out"
    if [ "$chaos" = 1 ]; then
        "$py" "$here/chaos_check.py" "$here/decks/in.$name"
    fi
done
du -ch "$here"/refs/*/{forces0.txt,final.txt,meta.json} | tail -n 1
