#!/bin/bash
# vorball against its peers on the same spheres: Voronota 1.29 (CPU, 1 thread and
# all threads) and the GPU Apollonius diagram of Plateau-Holleville et al. (TOG 2025).
#
# usage: peer_bench.sh VORBALL VORONOTA TOGPEER OUTDIR INPUT...
#   VORBALL   vorball binary;  VORONOTA  voronota binary;  TOGPEER  apo_vertices binary
#             (the peers are built apart, never by this script; '-' skips a peer)
#   INPUT     spheres as XYZR lines 'x y z r' (cif_to_xyzr.py, tile_input.py write them)
# For each INPUT, OUTDIR/NAME/ gets per tool: its vertex file (Voronota's format
# 'q1 q2 q3 q4 x y z r', 0-based ids), measure_TOOL.json (wall time, max RSS),
# verify_TOOL.json (`vorball verify --json`: certified / not a vertex / wrong
# coordinates / missing members / duplicate, and with --complete the vertices the
# file misses), and summary.json; OUTDIR/peer_bench.tsv gets one row per tool.
# Without --complete, 'missed_vs_union' counts the vertices some tool found and
# this one did not (all vertex files together through `vorball verify`, whose
# exact grouping merges the lines of one vertex).
# Environment (all optional):
#   TOOLS="vorball voronota1 voronotaN apo"  which runs to make
#   THREADS=N         threads of the parallel runs (default: nproc)
#   VORONOTA_PARTS=P  parts of calculate-vertices-in-parallel, a power of 2 (default 32,
#                     as the TOG paper's comparison)
#   VORBALL_DEVICE=D  auto|gpu|cpu|ref (default auto);  REPEAT=R  timed repeats of
#                     `vorball bench` and of apo's build (default 3)
#   APO_JOGGLE=R      also run apo on spheres joggled by R (the TOG paper uses 1e-3),
#                     judged against the joggled spheres it wrote
#   COMPLETE_MAX=N    use --complete (brute force) up to N spheres (default 400)
#   UNION_MAX_LINES=L skip the union check above L vertex lines in all (default 20000000)
#   TIMEOUT=S         kill a tool run after S seconds (default none)
#   KEEP_VERTICES=0   delete the vertex files after the checks (default 1: keep)
# Needs bash, python3 (standard library) and the binaries; nothing is built here.
set -u
if [ $# -lt 5 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
VORBALL=$1 VORONOTA=$2 TOGPEER=$3 OUTDIR=$4
shift 4
here=$(cd "$(dirname "$0")" && pwd)
measure="python3 $here/measure.py"
TOOLS=${TOOLS:-"vorball voronota1 voronotaN apo"}
THREADS=${THREADS:-$(nproc)}
VORONOTA_PARTS=${VORONOTA_PARTS:-32}
VORBALL_DEVICE=${VORBALL_DEVICE:-auto}
REPEAT=${REPEAT:-3}
APO_JOGGLE=${APO_JOGGLE:-}
COMPLETE_MAX=${COMPLETE_MAX:-400}
UNION_MAX_LINES=${UNION_MAX_LINES:-20000000}
TIMEOUT=${TIMEOUT:-}
KEEP_VERTICES=${KEEP_VERTICES:-1}
tmo=()
[ -n "$TIMEOUT" ] && tmo=(--timeout "$TIMEOUT")
mkdir -p "$OUTDIR" || exit 3
has() { case " $TOOLS " in *" $1 "*) return 0 ;; esac; return 1; }
log() { echo "peer_bench: $*" >&2; }

for in in "$@"; do
    [ -r "$in" ] || { log "cannot read $in"; exit 3; }
    name=$(basename "${in%.*}")
    d=$OUTDIR/$name
    mkdir -p "$d" || exit 3
    n=$(grep -c '[0-9]' "$in")
    complete=()
    [ "$n" -le "$COMPLETE_MAX" ] && complete=(--complete)
    log "$name: $n spheres, threads $THREADS"
    printf '{"input":"%s","spheres":%s,"threads":%s,"voronota_parts":%s,"vorball_device":"%s","host":"%s","nproc":%s}\n' \
        "$in" "$n" "$THREADS" "$VORONOTA_PARTS" "$VORBALL_DEVICE" "$(cat /proc/sys/kernel/hostname 2>/dev/null)" "$(nproc)" > "$d/run.json"
    files=()
    if has vorball && [ "$VORBALL" != - ]; then
        log "$name: vorball bench"
        "$VORBALL" bench --json --repeat "$REPEAT" --device "$VORBALL_DEVICE" --threads "$THREADS" \
            "$in" > "$d/vorball_bench.json" 2> "$d/vorball_bench.err"
        log "$name: vorball vertices"
        $measure "$d/measure_vorball.json" "${tmo[@]}" --stderr "$d/vorball.stats" -- \
            "$VORBALL" vertices --stats --device "$VORBALL_DEVICE" --threads "$THREADS" \
            --output-format voronota -o "$d/vorball.vertices" "$in"
        files+=(vorball)
    fi
    if has voronota1 && [ "$VORONOTA" != - ]; then
        log "$name: voronota calculate-vertices (1 thread)"
        $measure "$d/measure_voronota1.json" "${tmo[@]}" --env OMP_NUM_THREADS=1 --stdin "$in" \
            --stdout "$d/voronota1.vertices" --stderr "$d/voronota1.err" -- \
            "$VORONOTA" calculate-vertices
        files+=(voronota1)
    fi
    if has voronotaN && [ "$VORONOTA" != - ]; then
        log "$name: voronota calculate-vertices-in-parallel ($THREADS threads, $VORONOTA_PARTS parts)"
        $measure "$d/measure_voronotaN.json" "${tmo[@]}" --env OMP_NUM_THREADS="$THREADS" --stdin "$in" \
            --stdout "$d/voronotaN.vertices" --stderr "$d/voronotaN.err" -- \
            "$VORONOTA" calculate-vertices-in-parallel --method openmp --parts "$VORONOTA_PARTS"
        files+=(voronotaN)
    fi
    if has apo && [ "$TOGPEER" != - ]; then
        log "$name: apo (TOG 2025 GPU peer)"
        $measure "$d/measure_apo.json" "${tmo[@]}" --stdout "$d/apo.json" --stderr "$d/apo.err" -- \
            "$TOGPEER" --warmup 1 --repeat "$REPEAT" -o "$d/apo.vertices" "$in"
        files+=(apo)
        if [ -n "$APO_JOGGLE" ]; then
            log "$name: apo on spheres joggled by $APO_JOGGLE"
            $measure "$d/measure_apo_joggled.json" "${tmo[@]}" --stdout "$d/apo_joggled.json" \
                --stderr "$d/apo_joggled.err" -- "$TOGPEER" --warmup 1 --repeat "$REPEAT" \
                --joggle "$APO_JOGGLE" --sites-out "$d/apo_joggled.spheres" -o "$d/apo_joggled.vertices" "$in"
        fi
    fi
    # Each tool's file judged exactly against the spheres it was given.
    for t in "${files[@]}"; do
        [ -s "$d/$t.vertices" ] || { log "$name: $t wrote no vertices"; continue; }
        log "$name: verify $t ${complete[*]}"
        $measure "$d/measure_verify_$t.json" --stderr "$d/verify_$t.err" -- \
            "$VORBALL" verify "$in" "$d/$t.vertices" --json "${complete[@]}" -o "$d/verify_$t.json"
    done
    if [ -s "$d/apo_joggled.vertices" ]; then
        log "$name: verify apo_joggled (against its joggled spheres)"
        "$VORBALL" verify "$d/apo_joggled.spheres" "$d/apo_joggled.vertices" --json "${complete[@]}" \
            -o "$d/verify_apo_joggled.json" 2> "$d/verify_apo_joggled.err"
    fi
    # The union of all tools' vertices: one file, grouped exactly by verify.
    rm -f "$d/verify_union.json"
    if [ "${#files[@]}" -ge 2 ] && [ "${#complete[@]}" -eq 0 ]; then
        lines=0 have=()
        for t in "${files[@]}"; do
            if [ -s "$d/$t.vertices" ]; then
                lines=$((lines + $(wc -l < "$d/$t.vertices")))
                have+=("$t")
            fi
        done
        if [ "${#have[@]}" -lt 2 ]; then
            log "$name: union skipped (fewer than two vertex files)"
        elif [ "$lines" -le "$UNION_MAX_LINES" ]; then
            log "$name: union of ${have[*]} ($lines lines)"
            for t in "${have[@]}"; do cat "$d/$t.vertices"; done \
                | "$VORBALL" verify "$in" - --json -o "$d/verify_union.json" 2> "$d/verify_union.err"
            # Every line found by a second tool is a 'duplicate' problem: keep the counts
            # and the other problems only (the file would be as long as the union).
            python3 - "$d/verify_union.json" <<'EOF'
import re, sys
path = sys.argv[1]
kept, dropped = [], 0
with open(path) as f:
    for line in f:
        if line.startswith('{"line":') and '"class":"duplicate"' in line:
            dropped += 1
            continue
        kept.append(line)
text = re.sub(r",\s*\]", "\n]", "".join(kept))
text = text.replace('"problems":[', '"duplicate_lines_not_listed":%d,"problems":[' % dropped, 1)
open(path, "w").write(text)
EOF
        else
            log "$name: union skipped ($lines lines > UNION_MAX_LINES)"
        fi
    fi
    python3 "$here/peer_summary.py" "$d" "$OUTDIR/peer_bench.tsv" "${files[@]}" || exit 6
    if [ "$KEEP_VERTICES" = 0 ]; then
        rm -f "$d"/*.vertices "$d/apo_joggled.spheres"
    fi
done
