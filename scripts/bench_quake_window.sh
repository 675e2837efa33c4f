#!/usr/bin/env bash
# A window of a quake stage, two builds side by side: each run restarts SCENE from the step
# checkpoint CK (written with `--checkpoint-every N` inside the quake) and is timed from its
# first progress line ("  t = … s after …") to the STEPS-th after it, then stopped; the two
# builds alternate, PAIRS pairs, on RANKS ranks. Prints each run's seconds and Newton
# iterations over the window, and the ratio base/this of every pair with its range.
#
# Usage: scripts/bench_quake_window.sh BASE_CFRD THIS_CFRD SCENE CK [STEPS] [PAIRS] [RANKS]
#   BASE_CFRD, THIS_CFRD  two cfrd binaries (e.g. a base commit's release build and this one)
#   STEPS default 50, PAIRS default 3, RANKS default 2. Run it alone on the machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
base=${1:?usage: scripts/bench_quake_window.sh BASE_CFRD THIS_CFRD SCENE CK [STEPS] [PAIRS] [RANKS]}
this=${2:?}; scene=${3:?}; ck=${4:?}
steps=${5:-50}; pairs=${6:-3}; ranks=${7:-2}
source "$root/ci/env.sh"
unset MPIEXEC_TIMEOUT
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# window BIN OUT: prints "seconds newton_iterations" of STEPS steps after the first
window() {
    local log="$work/$2.log" pid t0="" t1="" n0="" n first last
    mpirun -n "$ranks" "$1" run "$scene" -o "$work/$2" --restart "$ck" --checkpoint none >"$log" 2>&1 &
    pid=$!
    while kill -0 "$pid" 2>/dev/null; do
        n=$(grep -c '^  t = ' "$log" || true)
        if [ -z "$n0" ] && [ "$n" -ge 1 ]; then n0=$n; t0=$(date +%s.%N); fi
        if [ -n "$n0" ] && [ "$n" -ge $((n0 + steps)) ]; then t1=$(date +%s.%N); break; fi
        sleep 0.1
    done
    kill "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    [ -n "$t1" ] || { echo "run $2 ended before $steps steps: $log" >&2; tail -5 "$log" >&2; exit 1; }
    first=$(grep '^  t = ' "$log" | sed -n "${n0}p" | sed 's/.*(\([0-9]*\) Newton.*/\1/')
    last=$(grep '^  t = ' "$log" | sed -n "$((n0 + steps))p" | sed 's/.*(\([0-9]*\) Newton.*/\1/')
    echo "$(echo "$t1 - $t0" | bc) $((last - first))"
}

ratios=()
for k in $(seq 1 "$pairs"); do
    read -r sb nb <<<"$(window "$base" "base_$k")"
    read -r st nt <<<"$(window "$this" "this_$k")"
    r=$(echo "scale=3; $sb / $st" | bc)
    ratios+=("$r")
    echo "pair $k: base ${sb} s (${nb} Newton), this ${st} s (${nt} Newton), base/this $r"
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{a[NR]=$1} END {print "base/this: median " a[int((NR+1)/2)] ", range " a[1] "-" a[NR]}'
