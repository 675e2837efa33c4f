#!/usr/bin/env bash
# A seed quake killed twice and restarted: from a post-impoundment
# checkpoint, runs the earthquake once uninterrupted and once killed (SIGKILL to mpirun and the
# ranks) after KILL_1 and again KILL_2 seconds, each time restarted from the step checkpoint
# the killed part left, and compares the last parts' results with `cfrd compare --tolerance 0`.
# Both runs write step checkpoints (a step checkpoint starts a fresh preconditioner, in the
# uninterrupted run too, which is what makes a restart exact).
#
# Usage: scripts/quake_kill_restart.sh SCENE CHECKPOINT RUN_DIR [RANKS] [KILL_1] [KILL_2]
#   SCENE       the quake scene, e.g. inputs/scenes/seed_coarse_gp_interface_quake.yaml
#   CHECKPOINT  its post-impoundment checkpoint (the checkpoint.h5 of a run stopped or killed
#               in the quake, or of `cfrd run SCENE --stop-after-stage` at the last static stage)
#   RUN_DIR     where the runs go (whole/, part_1/ .. part_3/ and their logs)
#   RANKS 2, KILL_1 90, KILL_2 120 (seconds of each killed part)
# Prints the time of the quake each part reached and the comparison; exits non-zero when the
# results differ.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$3"
scene=$1 start=$2 ranks=${4:-2}
kills=("${5:-90}" "${6:-120}")
unset MPIEXEC_TIMEOUT

run() { # out restart-from
    mpirun -n "$ranks" "$bin" run "$scene" --restart "$2" --checkpoint step -o "$1"
}
[ -f "$runs/whole/summary.json" ] || run "$runs/whole" "$start" > "$runs/whole.log" 2>&1
from=$start
for k in 1 2; do
    out="$runs/part_$k"
    rm -rf "$out"
    run "$out" "$from" > "$out.log" 2>&1 &
    sleep "${kills[$((k - 1))]}"
    pkill -KILL -f -- "-o $out" || true
    wait || true
    [ -f "$out/checkpoint.h5" ] || { echo "part $k left no checkpoint"; exit 1; }
    echo "part $k killed after ${kills[$((k - 1))]} s, at $(grep -o 't = [0-9.]* s after' "$out.log" | tail -1)"
    from="$out/checkpoint.h5"
done
run "$runs/part_3" "$from" > "$runs/part_3.log" 2>&1
"$bin" compare "$runs/whole" "$runs/part_3" --tolerance 0 --common
