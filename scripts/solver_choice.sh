#!/usr/bin/env bash
# The seed scenes with the canonical LU (their default: the whole placed system factored on every
# rank) against the distributed LU (MUMPS over all ranks, `solver.linear_solver:
# distributed_lu`), side by side in alternating runs on the same machine:
# wall time, Newton iterations, cut-backs and peak memory per rank of each run, and the
# largest difference of the slab table at the central section (seed Figs. 8, 9:
# fig08_slab_stress.csv) between the two solvers (the project allows 0.02 MPa and 0.1 cm).
#
# Usage: scripts/solver_choice.sh RUN_DIR [RANKS] [SCENE...]
#   RANKS 2; SCENE default: the three coarse seed scenes (static scenes: a copy with the solver
#   changed is run from RUN_DIR, so relative paths in it would not resolve). A run finished in
#   RUN_DIR/<scene>_<solver> (summary.json) is not repeated. Run it alone on the machine.
set -euo pipefail

source "$(dirname "${BASH_SOURCE[0]}")/run_dir_preamble.sh" "$1"
ranks=${2:-2}
shift $(($# < 2 ? $# : 2))
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(inputs/scenes/seed_coarse_{hyperbolic,mohr_coulomb,gp_interface}.yaml)

run() { # scene solver
    local name out
    name=$(basename "$1" .yaml)
    out="$runs/${name}_$2"
    [ -f "$out/summary.json" ] && return 0
    sed "s/linear_solver: canonical_lu/linear_solver: $2/" "$1" > "$runs/${name}_$2.yaml"
    grep -q "linear_solver: $2" "$runs/${name}_$2.yaml"
    /usr/bin/time -v mpirun -n "$ranks" "$bin" run "$runs/${name}_$2.yaml" -o "$out" \
        > "$out.log" 2>&1
}

summary() { # run directory
    python3 - "$1" <<'PY'
import json, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
mem = "/".join(f"{m / 2**20:.0f}" for m in s["peak_memory_bytes_per_rank"])
print(f"{s['total_seconds']:.1f} s, {s['newton_iterations']} Newton, {s['cutbacks']} cut-backs, "
      f"{s['factorizations']} factorizations, peak memory per rank {mem} MiB")
PY
}

slab_difference() { # a b: largest |difference| of sigma_s, sigma_a (MPa) and deflection (cm)
    paste -d, "$1/fig08_slab_stress.csv" "$2/fig08_slab_stress.csv" | awk -F, 'NR > 1 {
        for (k = 3; k <= 5; k++) { d = $k - $(k + 5); if (d < 0) d = -d; if (d > m[k]) m[k] = d }
    } END { printf "slab table: sigma_s %.4f MPa, sigma_a %.4f MPa, deflection %.4f cm\n",
                   m[3] / 1e6, m[4] / 1e6, m[5] * 100 }'
}

for scene in "${scenes[@]}"; do
    scene=$(realpath "$scene")
    name=$(basename "$scene" .yaml)
    for solver in canonical_lu distributed_lu; do
        run "$scene" "$solver"
        echo "$name $solver: $(summary "$runs/${name}_$solver")"
    done
    echo "$name: $(slab_difference "$runs/${name}_canonical_lu" "$runs/${name}_distributed_lu")"
done
