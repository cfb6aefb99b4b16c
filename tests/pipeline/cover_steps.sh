#!/bin/sh
# Where a device cover's time goes (--stats, bench --json; issue #30's
# per-step timers): per step of the device's launches (first tier, large,
# hand-off, huge, the first tier's reruns for handed patches that found no
# room) the kernel's seconds, the launches' wall seconds, launches and
# tasks; on the host the batches, the device thread's work after each
# read-back, the sinks, the CPU of whole host cells and of the resumed
# patches, the host threads' wait for the device and the device's wait for
# the host (the tail); per step the work (patches, the most of a task, the
# patches and tasks that ran out and ran again), and what the first tier's
# arenas held (the most records, labels and quadruples of a task that
# finished, its tasks past half its records or labels). Checked on PoCL (on
# a GPU the same code):
# - every column is printed, on ref too (zero there: no device);
# - sums within totals: a step's kernel seconds within its launches' wall,
#   the launches within cover_device_s, the device's batches and their
#   dispatch within the proposer's wall, the tail and the waits within it,
#   the CPU within threads x wall;
# - counts equal over two runs (launches, tasks, batches, resumed patches
#   and queued resumes), the resumed patches with CPU seconds;
# - the reruns apart from the first launch: with 16 words of handed patches
#   a cell (VORBALL_COVER_HAND_WORDS) the first tier runs again for the cells
#   that found no room, counted in cover_*_rerun, while cover_launches_first
#   stays 1 and the vertex rows stay ref's;
# - the steps' work: a protein fragment's cells that run out of 48 records
#   a first-tier slice counted as wasted, run again as tasks (four times as
#   many split at two levels), the patches each step kept summing to
#   cover_patches, with the same vertex rows as ref;
# - with the host threads resuming (VORBALL_COVER_RESUME_SPREAD=1, a GPU's
#   default) the queued resumes are counted, with no resume CPU lost.
# usage: cover_steps.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/cover_steps
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
# every cell to the device, so that what it hands does not depend on timing
export VORBALL_COVER_HOST_BACK=0
in=$corpus/inputs/sc_jitter12.xyzr
steps="first large handoff huge rerun"
cols="cover_device_s cover_batches cover_dispatch_s cover_sink_s cover_host_cells_cpu_s
cover_resume_cpu_s cover_resume_queued cover_host_wait_s cover_tail_s propose_s"
for s in $steps; do
    cols="$cols cover_kernel_${s}_s cover_launch_${s}_s cover_launches_$s cover_tasks_$s"
done
# le A B [SLACK]: A <= B + SLACK (reals; clocks read apart differ by ~1e-6)
le() { awk -v a="$1" -v b="$2" -v e="${3:-0.000005}" 'BEGIN { exit !(a <= b + e) }'; }
# check NAME: the columns of NAME.err present and consistent
check() {
    f=$1.err
    for c in $cols; do
        [ -n "$(stat "$c" "$f")" ] || fail "$1: no $c line"
    done
    dev=$(stat cover_device_s "$f") prop=$(stat propose_s "$f") sum=0
    for s in $steps; do
        k=$(stat "cover_kernel_${s}_s" "$f") l=$(stat "cover_launch_${s}_s" "$f")
        le "$k" "$l" || fail "$1: $s kernel $k s past its launches' $l s"
        sum=$(awk -v a="$sum" -v b="$l" 'BEGIN { print a + b }')
    done
    le "$sum" "$dev" || fail "$1: launches $sum s past cover_device_s $dev"
    busy=$(awk -v a="$dev" -v b="$(stat cover_dispatch_s "$f")" 'BEGIN { print a + b }')
    le "$busy" "$prop" || fail "$1: device and dispatch $busy s past propose_s $prop"
    for c in cover_tail_s cover_sink_s; do
        le "$(stat $c "$f")" "$prop" || fail "$1: $c past propose_s $prop"
    done
    le "$(stat cover_host_wait_s "$f")" "$prop" || fail "$1: host wait past 1 thread x $prop"
    cpu=$(awk -v a="$(stat cover_resume_cpu_s "$f")" -v b="$(stat cover_host_cells_cpu_s "$f")" \
        'BEGIN { print a + b }')
    le "$cpu" "$(awk -v p="$prop" 'BEGIN { print 2 * p }')" 0.01 ||
        fail "$1: resume and host cells $cpu CPU s past 2 threads x $prop"
    res=$(stat cover_resumed_patches "$f")
    [ "$res" -gt 0 ] || fail "$1: no patch resumed"
    awk -v c="$(stat cover_resume_cpu_s "$f")" 'BEGIN { exit !(c > 0) }' ||
        fail "$1: $res patches resumed in no CPU time"
    [ "$(stat cover_batches "$f")" -ge 1 ] || fail "$1: no batch counted"
}
counts() {
    for c in cover_batches cover_resumed_patches cover_resume_queued cover_host_cells; do
        printf '%s=%s ' "$c" "$(stat $c "$1.err")"
    done
    for s in $steps; do
        printf '%s=%s/%s ' "$s" "$(stat "cover_launches_$s" "$1.err")" \
            "$(stat "cover_tasks_$s" "$1.err")"
    done
}
run 0 ref.err "$vorball" vertices "$in" --device ref --threads 2 --stats -o ref.tsv
for c in $cols; do
    [ -n "$(stat "$c" ref.err)" ] || fail "ref: no $c line"
done
[ "$(stat cover_batches ref.err)" = 0 ] || fail "ref: device batches counted on host threads"
for r in a b; do
    run 0 "$r.err" "$vorball" vertices "$in" --device cpu --threads 2 --stats -o "$r.tsv"
    check "$r"
    [ "$(vertex_lines "$r.tsv")" = "$(vertex_lines ref.tsv)" ] || fail "$r: other vertices"
done
echo "a: $(counts a)"
[ "$(counts a)" = "$(counts b)" ] || fail "counts differ between runs: $(counts b)"
[ "$(stat cover_launches_first a.err)" = 1 ] || fail "a: one batch, not one first launch"
# What the first tier's arenas held (issue #30's memory plan): every cell
# finishes there on PoCL, so its most records are the host cover's most
# (ref's cover_max_cell_neighbours); none on ref.
[ "$(stat cover_first_records_max a.err)" = "$(stat cover_max_cell_neighbours ref.err)" ] ||
    fail "a: first tier's most records $(stat cover_first_records_max a.err), the host's" \
        "$(stat cover_max_cell_neighbours ref.err)"
[ "$(stat cover_first_labels_max a.err)" -gt 0 ] &&
    [ "$(stat cover_first_quadruples_max a.err)" -gt 0 ] || fail "a: no labels or quadruples held"
for c in records_max labels_max quadruples_max past_half; do
    [ "$(stat cover_first_$c ref.err)" = 0 ] || fail "ref: cover_first_$c on host threads"
done
[ "$(stat cover_launches_rerun a.err)" = 0 ] || fail "a: reruns with room for every patch"
# room for 16 words a cell: the cells that hand patches run again
VORBALL_COVER_HAND_WORDS=16 run 0 short.err "$vorball" vertices "$in" --device cpu --threads 2 \
    --stats -o short.tsv
check short
echo "short: $(counts short)"
[ "$(stat cover_launches_rerun short.err)" -gt 0 ] || fail "short: no rerun counted"
[ "$(stat cover_tasks_rerun short.err)" -gt 0 ] || fail "short: no rerun task counted"
[ "$(stat cover_launches_first short.err)" = 1 ] || fail "short: reruns counted as first launches"
[ "$(stat cover_resumed_patches short.err)" = "$(stat cover_resumed_patches a.err)" ] ||
    fail "short: other resumed patches"
[ "$(vertex_lines short.tsv)" = "$(vertex_lines ref.tsv)" ] || fail "short: other vertices"
# the host threads resume (a GPU's way)
VORBALL_COVER_RESUME_SPREAD=1 run 0 spread.err "$vorball" vertices "$in" --device cpu \
    --threads 2 --stats -o spread.tsv
check spread
echo "spread: $(counts spread)"
[ "$(stat cover_resume_queued spread.err)" -gt 0 ] || fail "spread: no resume queued"
[ "$(stat cover_resume_queued a.err)" = 0 ] || fail "a: resumes queued beside a CPU device"
# The steps' work (issue #30): with 48 records a first-tier slice
# (VORBALL_COVER_NB) and a large tier (VORBALL_COVER_TIER2), a protein
# fragment's cells that run out are counted as wasted (their patches and
# tasks) and run again as 24 T^2 tasks each, 96 T^2 split at two levels
# (VORBALL_COVER_TASK_SPLIT=2); what each step kept (its patches but the
# wasted ones) adds up to cover_patches, with no cell handed or left to the
# host; the most patches of a task is within its step's patches.
fr=$corpus/inputs/crambin_fragment.xyzr
run 0 wref.err "$vorball" vertices "$fr" --device ref --threads 2 -o wref.tsv
for sp in 1 2; do
    run 0 "w$sp.err" env VORBALL_COVER_NB=48 VORBALL_COVER_TIER2=64 \
        VORBALL_COVER_TASK_SPLIT=$sp "$vorball" vertices "$fr" --device cpu --threads 2 --stats \
        -o "w$sp.tsv"
    f=w$sp.err
    [ "$(vertex_lines "w$sp.tsv")" = "$(vertex_lines wref.tsv)" ] || fail "w$sp: other vertices"
    [ "$(stat cover_resumed_patches $f)" = 0 ] && [ "$(stat cover_host_cells $f)" = 0 ] ||
        fail "w$sp: cells handed or left to the host: the sum below does not hold"
    kept=0
    for s in $steps; do
        p=$(stat "cover_patches_$s" $f) w=$(stat "cover_wasted_patches_$s" $f)
        m=$(stat "cover_task_max_patches_$s" $f)
        [ "$w" -le "$p" ] && [ "$m" -le "$p" ] || fail "w$sp: $s wasted $w or most $m past $p"
        kept=$((kept + p - w))
    done
    [ "$kept" = "$(stat cover_patches $f)" ] ||
        fail "w$sp: the steps kept $kept patches, cover_patches $(stat cover_patches $f)"
    n=$(stat cover_wasted_tasks_first $f) t=$(stat cover_tasks_large $f)
    [ "$n" -gt 0 ] && [ "$(stat cover_wasted_patches_first $f)" -gt 0 ] ||
        fail "w$sp: no first-tier cell ran out of 48 records"
    [ $((t % (n * 24))) = 0 ] || fail "w$sp: $t large tasks for $n cells"
    # the first tier's cells that finished held at most its 48 records, some
    # of them past 24
    m=$(stat cover_first_records_max $f) h=$(stat cover_first_past_half $f)
    [ "$m" -gt 24 ] && [ "$m" -le 48 ] || fail "w$sp: first tier held $m records, not 25-48"
    [ "$h" -gt 0 ] && [ "$h" -le $(($(stat cover_tasks_first $f) - n)) ] ||
        fail "w$sp: $h first-tier tasks past half its arenas"
    [ "$(stat cover_task_max_patches_large $f)" -gt 0 ] || fail "w$sp: no large task's patches"
    echo "w$sp: first $(stat cover_patches_first $f) patches, $n cells ran out" \
        "($(stat cover_wasted_patches_first $f) patches), $t large tasks" \
        "($(stat cover_patches_large $f) patches, most $(stat cover_task_max_patches_large $f))"
done
[ "$(stat cover_tasks_large w2.err)" = $((4 * $(stat cover_tasks_large w1.err))) ] ||
    fail "split at two levels: not four times the tasks"
# bench --json: the same columns, in its cover_steps object
run 0 bench.err "$vorball" bench "$in" --device cpu --threads 2 --json -o bench.json
python3 - bench.json "$cols" <<'EOF' || fail "bench --json: cover_steps"
import json, sys
rows = json.load(open(sys.argv[1]))
st = rows[0]["cover_steps"]
want = [c for c in sys.argv[2].split() if c.startswith("cover_")]
missing = [c for c in want if c not in st]
assert not missing, missing
assert st["cover_resumed_patches"] > 0 and st["cover_batches"] >= 1, st
assert st["cover_kernel_first_s"] <= st["cover_launch_first_s"] + 5e-6, st
EOF
echo "ok: the cover's steps are counted, within their totals, the same over runs"
