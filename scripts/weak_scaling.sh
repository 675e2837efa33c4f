#!/usr/bin/env bash
# One stage of a seed scene rerun from a stage checkpoint on 1 and on 2 ranks (the
# weak-scaling table of one fill stage and of the impoundment over mesh sizes).
# Each run restarts from CHECKPOINT (written at the end of the stage before) and stops after one
# stage (`--stop-after-stage +1`); a checkpoint written on any rank count restarts on any other.
# Prints one CSV row per run: label, ranks, mesh DOFs, stage, wall seconds of the stage, Newton
# iterations, GMRES iterations, seconds per Newton iteration, GMRES iterations per Newton
# iteration, peak resident memory per rank (MiB, rank 0 / rank 1), all from the run's
# summary.json (`stage_seconds`, `peak_memory_bytes_per_rank`).
#
# Usage: scripts/weak_scaling.sh RUN_DIR LABEL SCENE CHECKPOINT [cfrd run arguments]
#   e.g. LABEL medium_fill_018; the runs go to RUN_DIR/LABEL_<n>rank, the rows are appended to
#   RUN_DIR/weak_scaling.csv. A run finished already (summary.json) is not repeated. Run it alone
#   on the machine: the figures are times.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$1"
[ $# -ge 4 ] || { echo "usage: $0 RUN_DIR LABEL SCENE CHECKPOINT [cfrd run arguments]" >&2; exit 2; }
label=$2
scene="$(realpath "$3")"
checkpoint="$(realpath "$4")"
shift 4
csv="$runs/weak_scaling.csv"
[ -f "$csv" ] || echo "label,ranks,dofs,stage,seconds,newton,gmres,seconds_per_newton,gmres_per_newton,peak_mib_per_rank" \
    > "$csv"

for ranks in 2 1; do
    out="$runs/${label}_${ranks}rank"
    if [ ! -f "$out/summary.json" ]; then
        rm -rf "$out"
        /usr/bin/time -v mpirun -n "$ranks" "$bin" run "$scene" -o "$out" -q \
            --restart "$checkpoint" --stop-after-stage +1 "$@" > "$out.log" 2>&1
    fi
    python3 - "$out/summary.json" "$label" "$ranks" >> "$csv" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
st = s["stage_seconds"][-1]
n, k = st["newton_iterations"], st["ksp_iterations"]
mem = "/".join(f"{m / 2**20:.0f}" for m in s["peak_memory_bytes_per_rank"])
print(f"{sys.argv[2]},{sys.argv[3]},{s['dofs']},{st['stage']},{st['seconds']:.1f},{n},{k},"
      f"{st['seconds'] / n:.3f},{k / n:.1f},{mem}")
PY
    tail -1 "$csv"
done
