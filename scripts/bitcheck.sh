#!/usr/bin/env bash
# Bit-identity check between two dmhs builds: every deck below is captured (`dmhs capture`: step-0
# forces and final state, %.17g-exact, and the thermo rows of the log) by both binaries at 1 and 2
# threads, and the files must be byte-identical. Used before and after a change that must not change results.
#   scripts/bitcheck.sh OLD_BINARY NEW_BINARY [OUTDIR]
# Prints one line per deck and thread count; exits 1 if any capture differs or fails in one build only.
set -uo pipefail
old=$(realpath "$1"); new=$(realpath "$2"); out=${3:-$(mktemp -d)}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
shared="$root/../shared/reference/lammps-decks"

# deck, then -var NAME VALUE pairs that shorten it
decks=()
for d in "$root"/lammps-refs/decks/in.*; do decks+=("$d"); done
decks+=(
  "$shared/in.poiseuille2d -var nsteps 200"
  "$shared/in.dambreak2d -var nsteps 200"
  "$shared/in.dambreak2d -var nsteps 100 -var rhosum 1"
  "$root/examples/bench/in.granular_bed -var nsettle 300 -var nsteps 100"
  "$root/examples/bench/in.beadspring2d -var nsteps 200"
  "$root/examples/bench/in.dambreak3d -var nsteps 30"
  "$root/examples/bench/in.lj3d -var n 8 -var nsteps 100"
  "$root/examples/heat/in.casting -var nsteps 300"
  "$root/examples/heat/in.conduct_hybrid"
  "$root/examples/heat/in.lava -var nsteps 300"
  "$root/examples/heat/in.stefan -var tend 0.5"
  "$root/examples/diffusion/in.cleaning -var nsteps 300"
  "$root/examples/diffusion/in.fick -var tend 0.05"
  "$root/examples/coupling/in.couette_bonded_wall -var nsteps 300"
  "$root/examples/dem/in.settle -var nsteps 1500"
)
mkdir -p "$out"
status=0
for entry in "${decks[@]}"; do
  read -r deck vars <<<"$entry"
  name=$(basename "$deck")${vars:+$(echo "$vars" | tr -d ' ')}
  [ -f "$deck" ] || { echo "MISSING $deck"; status=1; continue; }
  for t in 1 2; do
    a="$out/old/$name/t$t"; b="$out/new/$name/t$t"
    # each build runs in its own copy of the deck's folder, so the files the deck writes (dumps,
    # restarts) are compared too
    rc=()
    for side in a b; do
      dir=${!side}; bin=$old; [ $side = b ] && bin=$new
      rm -rf "$dir"; mkdir -p "$dir"; cp -r "$(dirname "$deck")" "$dir/deck"
      # shellcheck disable=SC2086
      (cd "$dir/deck" && timeout 600 "$bin" capture "$(basename "$deck")" --out "$dir/capture" -threads $t $vars >/dev/null 2>"$dir/stderr")
      rc+=($?)
      # thermo rows of the log (energies and virial too); timings differ from run to run
      grep -E '^ *-?[0-9]' "$dir/deck/log.dmhs" 2>/dev/null | grep -v '%' > "$dir/capture/thermo.txt"
      rm -f "$dir/deck/log.dmhs"
    done
    if [ "${rc[0]}" -ne 0 ] || [ "${rc[1]}" -ne 0 ]; then
      if [ "${rc[0]}" -ne "${rc[1]}" ]; then echo "DIFF  $name t$t: exit ${rc[0]} (old) vs ${rc[1]} (new)"; status=1; else echo "both fail (${rc[0]}) $name t$t: $(tail -c 300 "$b/stderr")"; fi
      continue
    fi
    if diff -r -q "$a/capture" "$b/capture" >/dev/null && diff -r -q "$a/deck" "$b/deck" >/dev/null; then
      echo "same  $name t$t ($(($(wc -l <"$a/capture/final.txt") - 1)) atoms)"
    else
      echo "DIFF  $name t$t: $(diff -r -q "$a" "$b" | grep -v stderr | head -3 | tr '\n' ' ')"; status=1
    fi
  done
done
exit $status
