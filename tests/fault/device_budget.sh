#!/bin/sh
# Device memory (issue 18, item 12): the sampler's device buffers stay
# within the device layer's budget, whatever size of batch it is handed,
# with output bytes identical to --device ref. With VORBALL_DEVICE_MEMORY_MIB
# small, the batches of crambin run in parts; the shim reports the largest
# clCreateBuffer. With "peak" as 5th argument (label long): on 3pqr (5352
# atoms) the default device (PoCL) peaks within 1.2 times the resident memory
# of --device cpu (it took 1.5 times: batches sized for a GPU).
# The cover's buffers (issue 30): --stats device_bytes_peak stays within the
# budget; cells forced out of the first tier (VORBALL_COVER_NB=64) in batches
# of 100 cells go, as root-patch tasks in launches that the budget splits, to
# the large tier made on demand within 32 MiB (16 MiB until PoCL's first
# tier kept the host's caches: 240 KiB more a slice, leaving no room for a
# large slice at 16), and to the host within 1 MiB (no room for a large
# slice): same bytes as --device ref either way; bench's runs each report
# their own peak. A budget
# that cannot hold the input stops with E142 (exit 46) and writes no file.
# VORBALL_COVER_KERNEL=group on a CPU device: W752 and the reference's vertices.
# usage: device_budget.sh VORBALL SHIM CORPUS_DIR WORK_DIR [peak]
vorball=$1 shim=$2 corpus=$3 work=$4/device_budget
. "$(dirname "$0")/shim_env.sh"
if [ "$5" = peak ]; then
    in=$corpus/data/3pqr.pqr
    [ -x /usr/bin/time ] || { echo "no /usr/bin/time: skipped"; exit 0; }
    /usr/bin/time -f '%M' -o "$work/cpu.kb" "$vorball" vertices --device cpu "$in" \
        -o "$work/cpu.tsv" 2> "$work/cpu.err" || fail "--device cpu failed"
    /usr/bin/time -f '%M' -o "$work/auto.kb" "$vorball" vertices "$in" \
        -o "$work/auto.tsv" 2> "$work/auto.err" || fail "the default device failed"
    cmp -s "$work/cpu.tsv" "$work/auto.tsv" || fail "the default device wrote other vertices"
    cpu=$(tail -n 1 "$work/cpu.kb") auto=$(tail -n 1 "$work/auto.kb")
    [ $((auto * 10)) -le $((cpu * 12)) ] ||
        fail "the default device peaked at $auto KB, --device cpu at $cpu KB"
    echo "ok: default device $auto KB, --device cpu $cpu KB"
    exit 0
fi
in=$corpus/data/1crn.pdb
run 0 "$work/ref.err" "$vorball" vertices --device ref "$in" -o "$work/ref.tsv"
for mib in 1 4; do
    rm -f "$work/counts.txt" "$work/v.tsv"
    VORBALL_DEVICE_MEMORY_MIB=$mib LD_PRELOAD=$shim VB_CLFAULT_COUNTS=$work/counts.txt \
        "$vorball" vertices "$in" -o "$work/v.tsv" > "$work/v.err" 2>&1 ||
        { cat "$work/v.err" >&2; fail "vertices with a budget of $mib MiB failed"; }
    grep -Eq 'W7[0-9]{2}' "$work/v.err" && { cat "$work/v.err" >&2; fail "a warning at $mib MiB"; }
    cmp -s "$work/v.tsv" "$work/ref.tsv" || fail "a budget of $mib MiB changed the vertices"
    grep -q '^clEnqueueNDRangeKernel ' "$work/counts.txt" || fail "no kernel ran on OpenCL"
    max=$(sed -n 's/^# max_buffer_bytes //p' "$work/counts.txt" | sort -n | tail -n 1)
    [ "$max" -le $((mib << 20)) ] || fail "a device buffer of $max bytes, budget $mib MiB"
    echo "budget $mib MiB: largest device buffer $max bytes"
done
stat() { awk -F'\t' -v k="$1" '$1 == k { print $2 }' "$2"; }
for mib in 32 1; do
    rm -f "$work/o.tsv"
    VORBALL_DEVICE_MEMORY_MIB=$mib VORBALL_COVER_NB=64 VORBALL_COVER_TIER2=64 VORBALL_COVER_BATCH=100 \
        "$vorball" vertices --stats "$in" -o "$work/o.tsv" > "$work/o.err" 2>&1 ||
        { cat "$work/o.err" >&2; fail "the forced overflow with $mib MiB failed"; }
    grep -Eq 'W7[0-9]{2}' "$work/o.err" && { cat "$work/o.err" >&2; fail "a warning at $mib MiB"; }
    cmp -s "$work/o.tsv" "$work/ref.tsv" || fail "the forced overflow at $mib MiB changed the vertices"
    peak=$(stat device_bytes_peak "$work/o.err") host=$(stat cover_host_cells "$work/o.err")
    [ -n "$peak" ] && [ "$peak" -gt 0 ] && [ "$peak" -le $((mib << 20)) ] ||
        fail "device_bytes_peak '$peak' at a budget of $mib MiB"
    eval "host_$mib=$host"
    echo "forced overflow, budget $mib MiB: device_bytes_peak $peak, cells on the host $host"
done
[ "$host_32" -lt "$host_1" ] || fail "the large tier took no cell at 32 MiB ($host_32 against $host_1)"
# The huge tier (gpu/vbg_cover_state.h): the large tier's tasks that ran out
# of its records run again on slices with more, made in its place; forced
# here with tiny large slices (the device takes every cell, so that the
# counts are the device's alone). Same bytes; the huge slices take cells the
# large ones could not, so fewer go to the host.
for t3 in 0 64; do
    rm -f "$work/h.tsv"
    VORBALL_COVER_HOST_BACK=0 VORBALL_COVER_NB=48 VORBALL_COVER_TIER2=64 VORBALL_COVER_BIG_NB=96 \
        VORBALL_COVER_TIER3=$t3 VORBALL_COVER_HUGE_NB=4096 \
        "$vorball" vertices --stats "$in" -o "$work/h.tsv" > "$work/h.err" 2>&1 ||
        { cat "$work/h.err" >&2; fail "the forced huge tier ($t3 slices) failed"; }
    cmp -s "$work/h.tsv" "$work/ref.tsv" || fail "the huge tier ($t3 slices) changed the vertices"
    eval "huge_$t3=$(stat cover_launches_huge "$work/h.err") hosted_$t3=$(stat cover_host_cells "$work/h.err")"
done
[ "$huge_0" = 0 ] && [ "$huge_64" -ge 1 ] && [ "$hosted_64" -lt "$hosted_0" ] ||
    fail "huge tier: launches $huge_0 / $huge_64, cells on the host $hosted_0 / $hosted_64"
echo "huge tier: cells on the host $hosted_0 without it, $hosted_64 with it ($huge_64 launches)"
# Stop 49's memory knobs (gpu/vbg_cover_state.h), same bytes: a handed-patch
# room of 8 words (VORBALL_COVER_HAND_CAP) leaves the first launch short on
# the sc crystal, whose cells then run again (cover_launches_rerun; the
# device takes every cell, VORBALL_COVER_HOST_BACK=0, else the host threads
# may take those cells first on a loaded machine); the large tier's
# quadruple room cut to 1 a task (VORBALL_COVER_BIG_QPER) holds fewer bytes.
sc=$corpus/equal-radius/sc.xyzr
run 0 "$work/scref.err" "$vorball" vertices --device ref "$sc" -o "$work/scref.tsv"
VORBALL_COVER_HAND_CAP=8 VORBALL_COVER_HOST_BACK=0 run 0 "$work/sch.err" "$vorball" vertices --device cpu --stats "$sc" \
    -o "$work/sch.tsv"
[ "$(vertex_lines "$work/sch.tsv")" = "$(vertex_lines "$work/scref.tsv")" ] ||
    fail "a handed-patch room of 8 words changed the vertices"
[ "$(stat cover_launches_rerun "$work/sch.err")" -ge 1 ] ||
    fail "a handed-patch room of 8 words ran no cell again"
for q in 16 1; do
    VORBALL_COVER_BIG_QPER=$q VORBALL_COVER_HOST_BACK=0 VORBALL_COVER_NB=64 VORBALL_COVER_TIER2=64 \
        run 0 "$work/q$q.err" "$vorball" vertices --device cpu --stats "$in" -o "$work/q$q.tsv"
    cmp -s "$work/q$q.tsv" "$work/ref.tsv" || fail "a quadruple room of $q a task changed the vertices"
done
[ "$(stat device_bytes_peak "$work/q1.err")" -lt "$(stat device_bytes_peak "$work/q16.err")" ] ||
    fail "a quadruple room of 1 a task held no fewer device bytes"
echo "stop 49 knobs: same vertices with a short handed-patch room and 1 quadruple a large task"
# bench keeps the device open: a run of another input starts without the
# buffers of the one before, so its device_bytes_peak is its own (the device
# takes every cell, VORBALL_COVER_HOST_BACK=0, so that the launches repeat).
peak_of() {
    VORBALL_COVER_HOST_BACK=0 VORBALL_COVER_NB=64 VORBALL_COVER_TIER2=64 \
        "$vorball" bench --json "$@" 2> /dev/null |
        sed -n 's/.*"input": "1crn.pdb".*"device_bytes_peak": \([0-9]*\).*/\1/p'
}
alone=$(peak_of "$in") after=$(peak_of "$corpus/data/1crn_apbs.pqr" "$in")
[ -n "$alone" ] && [ "$alone" = "$after" ] ||
    fail "1crn's device_bytes_peak in bench: '$alone' alone, '$after' after 1crn_apbs"
echo "bench: 1crn's device_bytes_peak $alone alone and after 1crn_apbs"
awk 'BEGIN { srand(7); for (i = 0; i < 40000; i++)
    printf "%.3f %.3f %.3f 1.5\n", rand() * 120, rand() * 120, rand() * 120 }' > "$work/big.xyzr"
rm -f "$work/big.tsv"
VORBALL_DEVICE_MEMORY_MIB=1 "$vorball" vertices "$work/big.xyzr" -o "$work/big.tsv" \
    > "$work/big.err" 2>&1
code=$?
[ "$code" -eq 46 ] && grep -q 'E142: the cover of 40000 spheres needs at least' "$work/big.err" ||
    { cat "$work/big.err" >&2; fail "a budget below the input exited $code, not E142"; }
[ -e "$work/big.tsv" ] && fail "E142 left an output file"
# The group kernel asked for on a CPU device (PoCL 3.1 crashed running it,
# stop 46): W752, the work-item kernel runs, the reference's vertices.
j=$corpus/inputs/jittered_fcc.xyzr
run 0 "$work/jref.err" "$vorball" vertices --device ref "$j" -o "$work/jref.tsv"
VORBALL_COVER_KERNEL=group run 0 "$work/jgrp.err" "$vorball" vertices --device cpu "$j" \
    -o "$work/jgrp.tsv"
expect_line "$work/jgrp.err" 'W752: VORBALL_COVER_KERNEL=group is ignored on .*a CPU device'
[ "$(vertex_lines "$work/jgrp.tsv")" = "$(vertex_lines "$work/jref.tsv")" ] ||
    fail "the group kernel's knob on a CPU device changed the vertices"
echo "ok: device buffers within the budget; W752 for the group kernel on a CPU device"
