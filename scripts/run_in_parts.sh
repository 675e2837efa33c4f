#!/usr/bin/env bash
# Runs a long staged scene in parts (for runs longer than a working session or a cluster
# job's time limit). Every part is a `cfrd run` in OUT/part_<k>;
# when a part stops before the end (killed, out of time), calling this script again with the
# same arguments restarts from the newest checkpoint (`--restart OUT/part_<k>/checkpoint.h5`,
# written at the end of stages, paced so that writing costs at most 2.5 % of the run) into OUT/part_<k+1>. A restarted run gives the same results,
# bit for bit, as an uninterrupted one at the same rank count.
#
# Usage: scripts/run_in_parts.sh SCENE OUT [RANKS] [-- extra `cfrd run` arguments]
#   RANKS defaults to 2. BIN overrides the binary (default: target/release/cfrd, built first).
#   PART_STAGES=N ends each part cleanly after N stages (`cfrd run --stop-after-stage +N`), e.g.
#   to fit a cluster job's time limit. Every part keeps the results.h5 of the stages it
#   completed up to its checkpoint (published at every stage checkpoint; parts killed by cfrd before that feature
#   have none), and the parts are drawn together with
#   `cfrd profiles SCENE OUT/part_1 OUT/part_2 ... -o OUT/profiles`.
# Writes OUT/parts.csv: part, first stage, last stage begun, wall seconds (from /usr/bin/time), peak
# resident memory of the largest rank in KiB, exit code. The finished part's summary.json holds
# the solver counters of the whole run (they are carried in the checkpoint); its results.h5 and
# figures hold the whole run (each part continues the results published beside the checkpoint
# it restarts from).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
[ $# -ge 2 ] || { echo "usage: $0 SCENE OUT [RANKS] [-- cfrd run arguments]" >&2; exit 2; }
scene="$(realpath "$1")"
out="$(realpath -m "$2")"
shift 2
ranks=2
if [ $# -gt 0 ] && [ "$1" != "--" ]; then ranks=$1; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
cd "$root"
if [ -z "${BIN:-}" ]; then
    cargo build --release --quiet
    BIN="${CARGO_TARGET_DIR:-$root/target}/release/cfrd"
fi
# a part runs for hours: no 600 s limit of ci/env.sh (which keeps a set MPIEXEC_TIMEOUT)
export MPIEXEC_TIMEOUT="${MPIEXEC_TIMEOUT:-86400}"
source ci/env.sh
mkdir -p "$out"
[ -f "$out/parts.csv" ] || echo "part,first_stage,last_stage_begun,wall_seconds,peak_rss_kib,exit_code" \
    > "$out/parts.csv"

# the newest part, and whether it finished the whole schedule
k=0
while [ -d "$out/part_$((k + 1))" ]; do k=$((k + 1)); done
if [ "$k" -gt 0 ] && [ -f "$out/part_$k/summary.json" ] \
    && ! grep -q '"stopped_after_stage"' "$out/part_$k/summary.json"; then
    echo "$out/part_$k finished the run already (summary.json)"
    exit 0
fi
# restart from the newest part that wrote a checkpoint (a part killed in its first stage has none)
part_args=()
[ -z "${PART_STAGES:-}" ] || part_args=(--stop-after-stage "+$PART_STAGES")
for ((j = k; j >= 1; j--)); do
    if [ -f "$out/part_$j/checkpoint.h5" ]; then
        part_args+=(--restart "$out/part_$j/checkpoint.h5")
        break
    fi
done
# a part that was killed leaves the file it was writing under a temporary name (as large as its
# results.h5, while its results.h5 and checkpoint.h5 stay whole): nothing reads it, so it goes
for stale in "$out"/part_*/.*.partial-*; do
    [ -e "$stale" ] && { echo "removing $stale (left by a killed part)"; rm -f "$stale"; }
done
part="$out/part_$((k + 1))"
log="$part.log"
echo "part $((k + 1)): $part (log $log)"
set +e
/usr/bin/time -v mpirun -n "$ranks" "$BIN" run "$scene" -o "$part" "${part_args[@]}" "$@" \
    > "$log" 2>&1
rc=$?
set -e
stages=$(tr '\r' '\n' < "$log" | sed -n "s/^stage \([0-9]*\)\/[0-9]* .*/\1/p")
first=$(echo "$stages" | head -1)
last=$(echo "$stages" | tail -1)
wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$log" \
    | awk -F: '{ s = 0; for (i = 1; i <= NF; i++) s = s * 60 + $i; print s }')
rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$log")
echo "$((k + 1)),${first:-},${last:-},${wall:-},${rss:-},$rc" >> "$out/parts.csv"
if [ -f "$part/summary.json" ] && ! grep -q '"stopped_after_stage"' "$part/summary.json"; then
    awk -F, 'NR > 1 { s += $4 } END { printf "finished: %d part(s), %.1f min in total\n", NR - 1, s / 60 }' \
        "$out/parts.csv"
else
    if [ "$rc" -eq 0 ]; then
        echo "part $((k + 1)) ended after stage ${last:-?} (PART_STAGES): run this again to continue"
        exit 0
    fi
    echo "part $((k + 1)) stopped (exit $rc) in stage ${last:-?}: run this again to continue" >&2
    exit 1
fi
