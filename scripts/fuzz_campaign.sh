#!/usr/bin/env bash
# Fuzz campaign over cfrd's input readers: every target of tests/fuzz runs RUNS
# inputs under libFuzzer (coverage-guided, AddressSanitizer, debug assertions; nightly
# toolchain), seeded from the repository's inputs, its kept corpus and tests/fuzz/seeds. Then
# the corpus is minimized into tests/fuzz/corpus/<target> (libFuzzer's merge gives the edges
# each input covers; a greedy set cover keeps at most CORPUS_CAP = 300 inputs, those adding the
# most edges), which tests/fuzz_corpus.rs replays on stable; any crasher is copied there too. Prints one table row per target: inputs tried, their outcomes (accepted,
# rejected with an error, skipped over the scene size budget), panics, aborts (out of memory,
# sanitizer, other signals), time-outs, wall time, code edges covered and corpus size.
# Logs: out/fuzz/<target>.log.
#
#   scripts/fuzz_campaign.sh [RUNS]        # RUNS per target, default 100000
#   TARGETS="gmsh scene" scripts/fuzz_campaign.sh 20000
#
# Limits per input: -timeout=10 s, -rss_limit_mb=2048, -malloc_limit_mb=2048, -max_len=8192.
# Dictionaries of scene keys and Gmsh section names: tests/fuzz/dict/<target>.dict.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-100000}
TARGETS=${TARGETS:-scene gmsh accel_csv accel_at2 state_codec lock_file checkpoint_inputs}
FUZZ=tests/fuzz
LOGS=out/fuzz
BIN=$FUZZ/target/x86_64-unknown-linux-gnu/release
CORPUS_CAP=${CORPUS_CAP:-300}
LIMITS=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=8192)

command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
cargo +nightly fuzz build --fuzz-dir "$FUZZ" --debug-assertions >&2
mkdir -p "$LOGS"

# Read-only seed folders of a target (the repository's own inputs and hand-written seeds).
seeds() {
    local dirs=("$FUZZ/seeds/$1")
    case $1 in
        scene) dirs+=(inputs/scenes) ;;
        gmsh) dirs+=(inputs/meshes) ;;
        accel_csv) dirs+=(inputs/accel) ;;
    esac
    for d in "${dirs[@]}"; do [ -d "$d" ] && echo "$d"; done
}

# The value after `key` in a log line such as `stat::number_of_executed_units: 100000`.
fuzz_stat() { grep -a "^stat::$1:" "$2" | tail -1 | awk '{print $2}'; }

# Counts of libFuzzer's findings in a log: panics, other aborts, time-outs.
findings() {
    local log=$1 panics aborts timeouts
    panics=$(grep -ac "panicked at" "$log" || true)
    timeouts=$(grep -ac "ERROR: libFuzzer: timeout" "$log" || true)
    aborts=$(grep -acE "ERROR: libFuzzer: (out-of-memory|deadly signal|malloc limit)|ERROR: AddressSanitizer" "$log" || true)
    aborts=$((aborts > panics ? aborts - panics : 0))
    echo "$panics $aborts $timeouts"
}

# Greedy set cover of the edges in a libFuzzer merge control file, at most $2 files: prints the
# chosen files, the one adding the most new edges first (lazy greedy).
cover() {
    python3 - "$1" "$2" <<'EOF'
import heapq, sys
lines = open(sys.argv[1]).read().split("\n")
n = int(lines[0])
files = lines[2 : 2 + n]
cov = {int(l.split()[1]): set(l.split()[2:]) for l in lines[2 + n :] if l.startswith("COV ")}
heap = [(-len(c), i) for i, c in cov.items()]
heapq.heapify(heap)
covered, chosen = set(), []
while heap and len(chosen) < int(sys.argv[2]):
    _, i = heapq.heappop(heap)
    gain = len(cov[i] - covered)
    if gain and heap and gain < -heap[0][0]:
        heapq.heappush(heap, (-gain, i))
    elif gain:
        chosen.append(i)
        covered |= cov[i]
print("\n".join(files[i] for i in chosen))
total = len(set().union(*cov.values())) if cov else 0
print(f"kept {len(chosen)} files covering {len(covered)} of {total} edges", file=sys.stderr)
EOF
}

# Replaces the corpus of target $1 (folder $2) by at most CORPUS_CAP files of it and of the seed
# folders ($3...) that cover their edges; crashers stay.
minimize() {
    local t=$1 corpus=$2 work
    shift 2
    work=$(mktemp -d)
    mkdir "$work/merged" "$work/keep"
    if ! "$BIN/$t" -merge=1 -merge_control_file="$work/control" "$work/merged" "$corpus" "$@" \
        "${LIMITS[@]}" >"$LOGS/$t.merge.log" 2>&1; then
        echo "  $t: the merge failed, the corpus is left as it is (see $LOGS/$t.merge.log)" >&2
        rm -rf "$work"
        return
    fi
    cover "$work/control" "$CORPUS_CAP" 2>>"$LOGS/$t.merge.log" | while read -r f; do
        cp "$f" "$work/keep/"
    done
    find "$corpus" -type f ! -name 'crash-*' ! -name 'oom-*' ! -name 'timeout-*' -delete
    cp "$work/keep"/* "$corpus/"
    rm -rf "$work"
}

printf '| target | inputs | accepted | rejected | skipped | panics | aborts | time-outs | time (s) | inputs/s | edges | corpus files | corpus KiB |\n'
printf '|---|---|---|---|---|---|---|---|---|---|---|---|---|\n'
status=0
for t in $TARGETS; do
    corpus=$FUZZ/corpus/$t
    artifacts=$FUZZ/artifacts/$t
    log=$LOGS/$t.log
    mkdir -p "$corpus" "$artifacts"
    mapfile -t seed_dirs < <(seeds "$t")
    dict=()
    [ -f "$FUZZ/dict/$t.dict" ] && dict=(-dict="$FUZZ/dict/$t.dict")
    start=$(date +%s.%N)
    rc=0
    "$BIN/$t" "$corpus" "${seed_dirs[@]}" -runs="$RUNS" "${LIMITS[@]}" "${dict[@]}" -print_final_stats=1 \
        -artifact_prefix="$artifacts/" >"$log" 2>&1 || rc=$?
    seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    for f in "$artifacts"/*; do [ -f "$f" ] && cp -n "$f" "$corpus/"; done
    if [ "$rc" -eq 0 ]; then minimize "$t" "$corpus" "${seed_dirs[@]}"; fi
    runs=$(fuzz_stat number_of_executed_units "$log")
    read -r accepted rejected skipped < <(grep -a "^cfrd-fuzz outcomes:" "$log" | tail -1 |
        sed -E 's/.*accepted=([0-9]+) rejected=([0-9]+) skipped=([0-9]+).*/\1 \2 \3/') || true
    read -r panics aborts timeouts < <(findings "$log") || true
    edges=$(grep -ao 'cov: [0-9]*' "$log" | tail -1 | awk '{print $2}')
    files=$(find "$corpus" -type f | wc -l)
    kib=$(find "$corpus" -type f -printf "%s\n" | awk '{ s += $1 } END { printf "%.0f", s / 1024 }')
    rate=$(awk -v n="${runs:-0}" -v s="$seconds" 'BEGIN { printf "%.0f", n / s }')
    printf '| %s | %s | %s | %s | %s | %s | %s | %s | %.0f | %s | %s | %s | %s |\n' "$t" "${runs:-?}" \
        "${accepted:-?}" "${rejected:-?}" "${skipped:-?}" "$panics" "$aborts" "$timeouts" \
        "$seconds" "$rate" "${edges:-?}" "$files" "$kib"
    if [ "$rc" -ne 0 ]; then
        echo "  $t: libFuzzer exited with $rc; the input is in $artifacts (see $log)" >&2
        status=1
    fi
done
exit $status
