#!/usr/bin/env bash
# The linear-elastic embankment quake (inputs/scenes/elastic_embankment_quake.yaml, 2,000
# hexahedra, 1,000 Newmark steps) in cfrd and in OpenSees, side by side, alternating: cfrd on
# one rank (`mpirun -n 1 cfrd run SCENE`), then scripts/opensees_embankment.py on the mesh that
# run wrote, PAIRS times. Prints each pair's seconds per time step (cfrd: its quake stage,
# summary.json; OpenSees: its analyze loop), their ratio and the largest difference of the two
# crest displacement histories relative to the largest displacement.
#
# usage: bash scripts/bench_linear_quake.sh OUT [PAIRS]   (CFRD=path/to/cfrd to choose a build;
# needs `pip install openseespy h5py`)
set -euo pipefail
out=${1:?usage: bash scripts/bench_linear_quake.sh OUT [PAIRS]}
pairs=${2:-3}
here=$(cd "$(dirname "$0")/.." && pwd)
cfrd=${CFRD:-$here/target/release/cfrd}
scene=$here/inputs/scenes/elastic_embankment_quake.yaml
mkdir -p "$out"
for i in $(seq 1 "$pairs"); do
  mpirun -n 1 "$cfrd" run "$scene" -o "$out/cfrd_$i" -q --overwrite
  crest=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['crest_node_id'])" "$out/cfrd_$i/quake_summary.json")
  python3 "$here/scripts/opensees_embankment.py" "$out/cfrd_$i/results.h5" \
    "$here/inputs/accel/seed_quake.csv" "$crest" "$out/opensees_$i.csv" > "$out/opensees_$i.log"
  python3 - "$out" "$i" <<'PY'
import json, sys
import numpy as np
out, i = sys.argv[1], sys.argv[2]
summary = json.load(open(f"{out}/cfrd_{i}/summary.json"))
quake = [s for s in summary["stage_seconds"] if s["stage"] == "quake"][0]
steps = quake["steps"]
cfrd_step = quake["seconds"] / steps
ops_seconds = float(open(f"{out}/opensees_{i}.log").read().split()[1])
ops_step = ops_seconds / 1000
c = np.genfromtxt(f"{out}/cfrd_{i}/quake_crest.csv", delimiter=",", names=True)
o = np.genfromtxt(f"{out}/opensees_{i}.csv", delimiter=",", names=True)
n = min(len(c), len(o))
diff = max(np.abs(c[k][:n] - o[k][:n]).max() for k in ["u_x", "u_y", "u_z"])
peak = max(np.abs(o[k][:n]).max() for k in ["u_x", "u_y", "u_z"])
print(f"pair {i}: cfrd {1000 * cfrd_step:.2f} ms per step ({steps} steps), OpenSees "
      f"{1000 * ops_step:.2f} ms, ratio {ops_step / cfrd_step:.2f}; crest histories differ by "
      f"{diff / peak:.2e} of the largest displacement {peak:.4f} m ({n} rows)")
PY
done
