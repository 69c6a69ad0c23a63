#!/usr/bin/env bash
# SPH stability map of the small 2D dam break (tests/decks/in.dambreak_dt): each resolution dx is run
# for 0.3 s of physical time at time steps dt = cfl * 0.25 h/c (h = 3 dx the kernel support, c = 20)
# with dmhs' stability guards on; prints "dx cfl steps result".
# dmhs' acoustic limit 0.25 hs/c (hs = h/2) is cfl = 0.5.
#   usage: scripts/stability-map.sh [dx...]      (default: 0.04 0.02 0.01)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin="$root/target/release/dmhs"
[ -x "$bin" ] || (cd "$root" && cargo build --release -q)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
dxs=("$@"); [ ${#dxs[@]} -gt 0 ] || dxs=(0.04 0.02 0.01)
echo "dx cfl steps result"
for dx in "${dxs[@]}"; do
    for cfl in 0.25 0.5 0.75 1 2 4; do
        steps=$(python3 -c "print(int(round(0.3/($cfl*0.25*3*$dx/20))))")
        if out=$("$bin" run "$root/tests/decks/in.dambreak_dt" -var dx "$dx" -var cfl "$cfl" \
                -var nsteps "$steps" -log none -screen none 2>&1); then
            result=stable
        else
            result="unstable ($(echo "$out" | grep -o 'run stopped at step [0-9]*' | head -1))"
        fi
        echo "$dx $cfl $steps $result"
    done
done
