#!/bin/sh
# The whole process of `vorball vertices` by stage (issue #30's fixed cost):
# for each input and device, REPEAT runs of `vertices --stats --device D IN
# -o OUT` (one untimed run first fills the program cache); the run with the
# smallest process_total_s is kept and its stage seconds written, wall and
# CPU (all threads): read, validate, run (set-up, proposer, certification),
# complete, write, free, total; then the run's own clock (setup_s, the
# set-up's seconds on its thread; setup_wait_s, what the proposer waited for
# it; propose_s, run_s, release_s) and the wall seconds of the whole command
# from outside (measure.py: process start and exit included).
# usage: process_stages.sh VORBALL OUTDIR REPEAT INPUT... -- DEVICE...
# OUTDIR/process_stages.tsv; the vertex files of the devices are compared
# (provenance lines aside) and the verdict written as the last column.
set -u
[ $# -ge 5 ] || { sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'; exit 2; }
vorball=$1 out=$2 repeat=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
inputs=""
while [ $# -gt 0 ] && [ "$1" != -- ]; do inputs="$inputs $1"; shift; done
[ $# -gt 1 ] || { echo "process_stages.sh: no devices after --" >&2; exit 2; }
shift
mkdir -p "$out" || exit 1
fields="process_read_s process_read_cpu_s process_validate_s process_validate_cpu_s
process_run_s process_run_cpu_s process_complete_s process_complete_cpu_s process_write_s
process_write_cpu_s process_free_s process_free_cpu_s process_total_s process_total_cpu_s
setup_s setup_wait_s propose_s run_s release_s"
printf 'input\tdevice\tbackend\tcommand_wall_s' > "$out/process_stages.tsv"
for f in $fields; do printf '\t%s' "$f" >> "$out/process_stages.tsv"; done
printf '\tsame_as_first\n' >> "$out/process_stages.tsv"
for in in $inputs; do
    name=$(basename "$in")
    first=""
    for dev in "$@"; do
        "$vorball" vertices --quiet --device "$dev" "$in" -o "$out/v.tsv" 2> /dev/null
        best="" bestt=""
        r=1
        while [ "$r" -le "$repeat" ]; do
            python3 "$here/measure.py" "$out/m.json" --stderr "$out/s$r.err" -- \
                "$vorball" vertices --quiet --stats --device "$dev" "$in" -o "$out/v.tsv"
            t=$(awk -F'\t' '$1 == "process_total_s" {print $2}' "$out/s$r.err")
            w=$(python3 -c 'import json,sys; print("%.3f" % json.load(open(sys.argv[1]))["wall_s"])' "$out/m.json")
            echo "$w" > "$out/s$r.wall"
            if [ -z "$bestt" ] || awk -v a="$t" -v b="$bestt" 'BEGIN {exit !(a < b)}'; then
                best=$r bestt=$t
            fi
            r=$((r + 1))
        done
        grep -v '^# \(options\|input\|tool\)' "$out/v.tsv" > "$out/$dev.cmp"
        same=-
        if [ -z "$first" ]; then first=$out/$dev.cmp; else
            cmp -s "$first" "$out/$dev.cmp" && same=yes || same=NO; fi
        e=$out/s$best.err
        printf '%s\t%s\t%s\t%s' "$name" "$dev" "$(awk -F'\t' '$1 == "backend" {print $2}' "$e")" \
            "$(cat "$out/s$best.wall")" >> "$out/process_stages.tsv"
        for f in $fields; do
            printf '\t%s' "$(awk -F'\t' -v k="$f" '$1 == k {print $2}' "$e")" >> "$out/process_stages.tsv"
        done
        printf '\t%s\n' "$same" >> "$out/process_stages.tsv"
        rm -f "$out"/s*.err "$out"/s*.wall "$out/m.json"
    done
    rm -f "$out"/*.cmp "$out/v.tsv"
done
cat "$out/process_stages.tsv"
