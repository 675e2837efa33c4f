#!/usr/bin/env bash
# Side-by-side benchmark: this working tree's build against a base commit's build on
# the same machine in the same session, in alternating pairs, so that machine-to-machine and
# hour-to-hour differences cancel in the ratio. Each run solves SCENE on RANKS ranks; the wall
# time is `total_seconds` of its summary.json (read to results, what a user waits for). The
# first pair is a warm-up and not counted. At the end the two builds' results are compared with
# `cfrd compare` (a speed-up that changes results is not a speed-up).
#
# Usage: scripts/bench_side_by_side.sh BASE [SCENE] [PAIRS] [RANKS]
#   BASE    a commit (e.g. main~3), built in a temporary worktree into target/bench-base/
#   SCENE   default inputs/scenes/seed_coarse_hyperbolic.yaml; PAIRS default 5; RANKS default 2
#   RUN_ARGS  (environment) more arguments of every `cfrd run`, e.g. a part of a scene:
#           RUN_ARGS="--restart CK --stop-after-stage 22" (CK a stage checkpoint of SCENE)
#   CHECKPOINT  (environment) `--checkpoint` of every run, default none (no checkpoint and no
#           results published before the end); stage measures the writes at the stages' ends too
# Prints one line per run and a summary: medians, the ratio this/base of the medians and the
# range of the pairwise ratios. Run it alone on the machine.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
base=${1:?usage: scripts/bench_side_by_side.sh BASE [SCENE] [PAIRS] [RANKS]}
scene=${2:-inputs/scenes/seed_coarse_hyperbolic.yaml}
pairs=${3:-5}
ranks=${4:-2}
source ci/env.sh
export MPIEXEC_TIMEOUT=7200

this_target="${CARGO_TARGET_DIR:-$root/target}"
base_target="$this_target/bench-base"
work=$(mktemp -d)
trap 'git worktree remove --force "$work/base" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git worktree add --detach "$work/base" "$base" >/dev/null
cargo build --release --locked --quiet
(cd "$work/base" && CARGO_TARGET_DIR="$base_target" cargo build --release --locked --quiet)
declare -A bin=([this]="$this_target/release/cfrd" [base]="$base_target/release/cfrd")

# run WHICH K: one run of SCENE with WHICH's build into $work/WHICH_K; prints its total_seconds
run() {
    local out="$work/$1_$2"
    # shellcheck disable=SC2086 # RUN_ARGS is a list of arguments
    mpirun -n "$ranks" "${bin[$1]}" run "$root/$scene" -o "$out" -q --checkpoint "${CHECKPOINT:-none}" ${RUN_ARGS:-} >"$out.log" 2>&1 \
        || { echo "the $1 build failed on $scene, see $out.log" >&2; exit 1; }
    python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["total_seconds"])' "$out/summary.json"
}

this_times=()
base_times=()
for k in $(seq 0 "$pairs"); do
    order=(base this)
    [ $((k % 2)) = 1 ] && order=(this base)
    for w in "${order[@]}"; do
        t=$(run "$w" "$k")
        echo "pair $k $w: ${t} s$([ "$k" = 0 ] && echo ' (warm-up, not counted)')"
        if [ "$k" -gt 0 ]; then
            if [ "$w" = this ]; then this_times+=("$t"); else base_times+=("$t"); fi
        fi
    done
done

python3 - "${this_times[*]}" "${base_times[*]}" "$base" "$scene" "$ranks" <<'EOF'
import statistics, sys
this = [float(x) for x in sys.argv[1].split()]
base = [float(x) for x in sys.argv[2].split()]
ratios = [a / b for a, b in zip(this, base)]
mt, mb = statistics.median(this), statistics.median(base)
print(f"{sys.argv[4]} on {sys.argv[5]} ranks, {len(this)} pairs:")
print(f"  this build: median {mt:.2f} s (range {min(this):.2f}-{max(this):.2f})")
print(f"  base {sys.argv[3]}: median {mb:.2f} s (range {min(base):.2f}-{max(base):.2f})")
print(f"  ratio this/base of the medians {mt / mb:.3f}; pairwise ratios {min(ratios):.3f}-{max(ratios):.3f}")
EOF
echo "results of the two builds (cfrd compare, base as reference):"
"${bin[this]}" compare "$work/base_1" "$work/this_1" | tail -n 5
