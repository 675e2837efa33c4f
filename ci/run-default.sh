#!/usr/bin/env bash
# One command: install what is missing, build, and run the main job, the coarse seed dam (Liu,
# Kong & Zou 2015): generalized-plasticity rockfill placed in 8 fill layers, the face slab in
# three stages on a GP slab-cushion interface, vertical and perimetric joints, impoundment to
# el. 2840 m; 2 ranks, about half a minute of solving (`cargo doc --open`, module `performance`).
#
# Usage: bash ci/run-default.sh [OUT]      (OUT defaults to out/seed_coarse)
#   SCENE=inputs/scenes/seed_coarse_hyperbolic.yaml picks another scene, RANKS=N another rank count.
# Running it again replaces OUT: the run goes into OUT.partial and is moved to OUT when it
# has finished, so a failed run leaves the previous results alone.
set -euo pipefail
cd "$(dirname "$0")/.."
bash ci/install-deps.sh
source ci/env.sh
cargo build --release --locked
bin="${CARGO_TARGET_DIR:-target}/release/cfrd"
scene=${SCENE:-inputs/scenes/seed_coarse_gp_interface.yaml}
ranks=${RANKS:-2}
out=${1:-out/seed_coarse}
out=${out%/}
marker=.cfrd-run-default # written into every output directory of this script

if [ -e "$out" ] && [ ! -f "$out/$marker" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
    echo "error: $out exists and was not written by ci/run-default.sh; give another directory" >&2
    exit 2
fi
rm -rf "$out.partial"
mkdir -p "$out.partial"
touch "$out.partial/$marker"
mpirun -n "$ranks" "$bin" run "$scene" -o "$out.partial"
rm -rf "$out"
mv "$out.partial" "$out"

cat <<EOF

Done: $scene on $ranks ranks, results in $out/
  seed Figs. 7-11 (PNG plot, CSV table each):
    $out/fig07_dam_displacement.png   settlement and horizontal displacement, crest vertical
    $out/fig08_slab_stress.png        slab stress along the slope and the axis, central section
    $out/fig09_slab_deflection.png    slab deflection
    $out/fig10_probe_I-A.png          stress path of interface element I-A (el. 2711 m)
    $out/fig11_interface.png          interface jumps and opening after impoundment
  $out/results.xdmf   every stage's fields: open in ParaView (data in results.h5)
  $out/summary.json   run summary: wall times, Newton iterations, cut-backs, memory
  $out/checkpoint.h5  last stage's checkpoint (cfrd run --restart)
Documentation: cargo doc --open (modules guide, verification, performance).
EOF
