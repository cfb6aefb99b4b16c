#!/bin/bash
# The host path against Voronota on one thread (issue #30, "CPU path"):
# `vorball vertices --threads 1` on each device (ref: plain C; cpu: PoCL
# with one thread) and Voronota's `calculate-vertices` on the same balls,
# in alternating rounds, CPU time (user + sys) from /usr/bin/time -v.
#
# usage: cpu_vs_voronota.sh VORONOTA OUTDIR ROUNDS INPUT...
#   VORONOTA  voronota binary (built apart, never by this script; '-' skips it)
#   INPUT     balls as XYZR lines 'x y z r' (cif_to_xyzr.py writes them);
#             Voronota reads the same lines on stdin
# Environment (all optional):
#   VORBALLS="NAME=PATH ..."  vorball binaries to compare (default
#                             "vorball=<repo>/build/cli/vorball"), e.g. a
#                             build of main beside the branch's
#   DEVICES="ref cpu"         vorball devices
#   PERF=1                    also one `perf record` run per binary and device
#                             (after the timed rounds): CPU samples split into
#                             cover, certification and the rest by function
# OUTDIR/runs.tsv: one row per run (input, round, tool, device, cpu_s,
# user_s, sys_s, wall_s, max_rss_kib, vertices, quadruples,
# certify_after_s, load1, and vorball's CPU seconds per process stage from
# --stats: read, validate, run (cover and certification), complete,
# write); OUTDIR/summary.tsv: per input, tool and device the
# median and range of cpu_s, the ratio to Voronota's median and the
# stages' medians; the vertex
# files of every vorball binary and device are compared byte for byte
# (provenance lines aside: '# tool' and '# options') and the verdict is
# the last column; OUTDIR/perf_split.tsv with PERF=1. The machine's load
# (/proc/loadavg) is written beside each run.
set -u
if [ $# -lt 4 ]; then
    sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'
    exit 2
fi
VORONOTA=$1 OUT=$2 ROUNDS=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
VORBALLS=${VORBALLS:-"vorball=$here/../../build/cli/vorball"}
DEVICES=${DEVICES:-"ref cpu"}
mkdir -p "$OUT" || exit 3
runs=$OUT/runs.tsv
stages="read validate run complete write"
printf 'input\tround\ttool\tdevice\tcpu_s\tuser_s\tsys_s\twall_s\tmax_rss_kib\tvertices\tquadruples\tcertify_after_s\tload1' > "$runs"
for st in $stages; do printf '\t%s_cpu_s' "$st" >> "$runs"; done
echo >> "$runs"

# timed RUNFILE -- CMD...: /usr/bin/time -v of CMD, its fields printed tab-separated
timed() {
    local tf=$1
    shift 2
    /usr/bin/time -v -o "$tf" "$@"
    awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} /Maximum resident/ {m = $2}
        /Elapsed \(wall/ {n = split($2, p, ":"); w = 0; for (i = 1; i <= n; i++) w = w * 60 + p[i]}
        END {printf "%.2f\t%.2f\t%.2f\t%.2f\t%s", u + s, u, s, w, m}' "$tf"
}
stat_of() { awk -F'\t' -v k="$2" '$1 == k {print $2}' "$1"; }

for in in "$@"; do
    [ -r "$in" ] || { echo "cpu_vs_voronota: cannot read $in" >&2; exit 3; }
    name=$(basename "${in%.*}")
    for r in $(seq 1 "$ROUNDS"); do
        for vb in $VORBALLS; do
            tool=${vb%%=*} bin=${vb#*=}
            for dev in $DEVICES; do
                base=$OUT/$name.$tool.$dev
                load=$(cut -d' ' -f1 /proc/loadavg)
                t=$(POCL_MAX_PTHREAD_COUNT=1 POCL_CPU_MAX_CU_COUNT=1 timed "$base.time" -- \
                    "$bin" vertices --device "$dev" --threads 1 --stats -o "$base.tsv" "$in" \
                    2> "$base.stats")
                printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s' "$name" "$r" "$tool" "$dev" "$t" \
                    "$(stat_of "$base.stats" certified_vertices)" \
                    "$(stat_of "$base.stats" cover_quadruples)" \
                    "$(stat_of "$base.stats" certify_after_s)" "$load" >> "$runs"
                for st in $stages; do
                    printf '\t%s' "$(stat_of "$base.stats" "process_${st}_cpu_s")" >> "$runs"
                done
                echo >> "$runs"
            done
        done
        if [ "$VORONOTA" != - ]; then
            load=$(cut -d' ' -f1 /proc/loadavg)
            t=$(OMP_NUM_THREADS=1 timed "$OUT/$name.voronota.time" -- sh -c \
                '"$0" calculate-vertices < "$1" > "$2"' "$VORONOTA" "$in" "$OUT/$name.voronota.vertices")
            printf '%s\t%s\tvoronota\t1 thread\t%s\t%s\t-\t-\t%s\n' "$name" "$r" "$t" \
                "$(grep -c . "$OUT/$name.voronota.vertices")" "$load" >> "$runs"
        fi
    done
    # Byte identity of the vertex files (provenance lines aside).
    first=
    for f in "$OUT/$name".*.tsv; do
        grep -v '^# \(tool\|options\)' "$f" > "$f.cmp"
        if [ -z "$first" ]; then first=$f.cmp; else
            cmp -s "$first" "$f.cmp" || echo "DIFFERENT $f" >> "$OUT/$name.identity"; fi
    done
    [ -s "$OUT/$name.identity" ] || echo "identical: $(cd "$OUT" && ls "$name".*.tsv | tr '\n' ' ')" \
        > "$OUT/$name.identity"
    rm -f "$OUT/$name".*.cmp
done

python3 - "$runs" "$OUT" > "$OUT/summary.tsv" <<'EOF'
import os, statistics, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1])][1:]
out = sys.argv[2]
by = {}
for r in rows:
    by.setdefault((r[0], r[2], r[3]), []).append(float(r[4]))
head = open(sys.argv[1]).readline().rstrip("\n").split("\t")
stage_cols = [k for k, h in enumerate(head) if h.endswith("_cpu_s")]
print("\t".join(["input", "tool", "device", "runs", "cpu_s_median", "cpu_s_min", "cpu_s_max",
                 "ratio_to_voronota", "load1", "identity"] +
                [head[k] + "_median" for k in stage_cols]))
for (inp, tool, dev), v in by.items():
    vor = by.get((inp, "voronota", "1 thread"))
    ratio = "%.3f" % (statistics.median(v) / statistics.median(vor)) if vor else "-"
    loads = [float(r[12]) for r in rows if (r[0], r[2], r[3]) == (inp, tool, dev)]
    ident = open(os.path.join(out, inp + ".identity")).read().split(":")[0].strip()
    print("\t".join([inp, tool, dev, str(len(v)), "%.2f" % statistics.median(v),
                     "%.2f" % min(v), "%.2f" % max(v), ratio,
                     "%.1f-%.1f" % (min(loads), max(loads)),
                     ident if tool != "voronota" else "-"] +
                    ["%.3f" % statistics.median(float(r[k]) for r in rows
                                                if (r[0], r[2], r[3]) == (inp, tool, dev))
                     if tool != "voronota" else "-" for k in stage_cols]))
EOF
cat "$OUT/summary.tsv"

# Where the CPU goes: one perf run per binary and device, samples by stage.
if [ "${PERF:-0}" = 1 ]; then
    printf 'input\ttool\tdevice\tsamples\tcover\tcertification\tother\n' > "$OUT/perf_split.tsv"
    for in in "$@"; do
        name=$(basename "${in%.*}")
        for vb in $VORBALLS; do
            tool=${vb%%=*} bin=${vb#*=}
            for dev in $DEVICES; do
                pd=$OUT/$name.$tool.$dev.perf
                POCL_MAX_PTHREAD_COUNT=1 POCL_CPU_MAX_CU_COUNT=1 perf record -q -F 499 -o "$pd" -- \
                    "$bin" vertices --device "$dev" --threads 1 -o /dev/null "$in" 2> /dev/null
                perf report -i "$pd" --no-children --sort symbol --stdio 2> /dev/null |
                    python3 -c '
import re, sys
name, tool, dev = sys.argv[1:4]
cover = re.compile(r"vbq_|vb_cover_cell|cover_|_pocl_kernel|workgroup|vbs_face_dir")
cert = re.compile(r"judge|vbx_|certif|__gmp|mpfr|vbv_|qf_|ia_of|cert_")
share = {"cover": 0.0, "cert": 0.0, "other": 0.0}
n = "0"
for line in sys.stdin:
    m = re.match(r"# Samples: (\S+)", line)
    if m:
        n = m.group(1)
    m = re.match(r"\s+([0-9.]+)%\s+\[\.\]\s+(\S+)", line)
    if not m:
        continue
    p, sym = float(m.group(1)), m.group(2)
    k = "cover" if cover.search(sym) else "cert" if cert.search(sym) else "other"
    share[k] += p
print("\t".join([name, tool, dev, n] + ["%.1f%%" % share[k] for k in ("cover", "cert", "other")]))
' "$name" "$tool" "$dev" >> "$OUT/perf_split.tsv"
                rm -f "$pd"
            done
        done
    done
    cat "$OUT/perf_split.tsv"
fi
