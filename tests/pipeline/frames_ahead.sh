#!/bin/sh
# Issue 33: frames in flight. `vorball channels` over the 10-frame XTC of
# the MD trajectory reads and runs the front half of the next frames on a
# reader thread (VORBALL_FRAMES_AHEAD frames ahead, 0: the sequential loop):
# table, statistics, centrelines and the JSON (less its clocks) must be the
# same bytes as the sequential loop's at every depth, thread count and
# device (reference and PoCL), the warnings in the same order, a --frames
# selection the same rows, and a trajectory cut inside a frame the same
# exit, the same error and no table. The components labelled on the device
# (PoCL) give the reference's bytes too, and with the clearances computed
# on the device (a GPU's host analysis) on one and two threads.
# usage: frames_ahead.sh VORBALL CORPUS WORKDIR
vorball=$1 corpus=$2 work=$3
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/frames_ahead"
top="$corpus/data/ngl_md_ascii_trj.pdb" xtc="$corpus/data/ngl_md_10frames.xtc"
# One frame in analysis at a time, so that depth 0 is the sequential loop
# on any machine (frames_inflight.sh runs the wider windows).
export VORBALL_FRAMES_IN_FLIGHT=1

# channels NAME DEPTH THREADS ARGS...: one run, its outputs named NAME.*
# and its stderr without the closing timing line in NAME.err.
channels() {
    name=$1 depth=$2 threads=$3
    shift 3
    VORBALL_FRAMES_AHEAD=$depth VORBALL_THREADS=$threads run 0 "$name.log" "$vorball" channels \
        "$top" --traj "$xtc" --grid 64 -o "$name.csv" --centerlines "$name.pdb" \
        --stats-file "$name.stats" "$@"
    grep -v '^vorball channels: [0-9]* frame' "$name.log" > "$name.err"
    # The statistics less their clocks (the ms_ columns).
    cut -d, -f1-12,18-24 "$name.stats" > "$name.st"
}

same() {
    for ext in csv pdb st err; do
        cmp -s "$1.$ext" "$2.$ext" || { diff "$1.$ext" "$2.$ext" | head -20 >&2; fail "$2.$ext differs from $1.$ext"; }
    done
}

channels seq 0 2 --device ref
# Ten frames of 183 atoms, each with rows in the table.
[ "$(tail -n +2 seq.stats | wc -l)" -eq 10 ] || fail "seq.stats: $(tail -n +2 seq.stats | wc -l) frames, expected 10"
[ "$(tail -n +2 seq.stats | cut -d, -f1 | tr '\n' ' ')" = "0 1 2 3 4 5 6 7 8 9 " ] ||
    fail "seq.stats: frames $(tail -n +2 seq.stats | cut -d, -f1 | tr '\n' ' ')"
[ "$(tail -n +2 seq.csv | wc -l)" -ge 10 ] || fail "seq.csv: fewer rows than frames"
for d in 1 2 8; do
    for t in 1 2; do
        channels "a${d}t$t" "$d" "$t" --device ref
        same seq "a${d}t$t"
    done
done
# --atoms of a trajectory: the first frame's atoms as analysed, 183 rows,
# its coordinates the XTC's doubles (a frame has no decimals; it crashed).
VORBALL_THREADS=2 run 0 atoms.log "$vorball" channels "$top" --traj "$xtc" --grid 64 --device ref \
    -o atoms.csv --atoms atoms.tsv --frames 0:2
[ "$(grep -c '^[0-9]' atoms.tsv)" -eq 183 ] || fail "atoms.tsv: $(grep -c '^[0-9]' atoms.tsv) rows, expected 183"
grep -q '^0	.	ILE	348	.	N	N	.	1	6	32.02000' atoms.tsv || fail "atoms.tsv: atom 0 is not the XTC's N"
# Unset: the default depth (2) is the reader thread too, same bytes.
VORBALL_THREADS=2 run 0 def.log "$vorball" channels "$top" --traj "$xtc" --grid 64 --device ref -o def.csv
cmp -s seq.csv def.csv || fail "default depth: table differs"

# The OpenCL pipe (PoCL) on the reader's thread against the sequential reference.
channels pocl 2 2 --device cpu
for ext in csv pdb st; do
    cmp -s seq.$ext pocl.$ext || fail "PoCL in flight: pocl.$ext differs from the sequential reference"
done

# The components labelled on the device (channels.cl's vbc_cc_*, forced on
# PoCL by VORBALL_DEVICE_GRAPH=1; the host checks them): the same bytes, on the
# trajectory and on a corpus structure.
VORBALL_DEVICE_GRAPH=1 channels pocl_cc 2 2 --device cpu
for ext in csv pdb st; do
    cmp -s seq.$ext pocl_cc.$ext || fail "device components: pocl_cc.$ext differs from the reference"
done
# The clearances computed on the device as well (a GPU's host analysis:
# given clearances and labels), on one and on two analysis threads.
for t in 1 2; do
    VORBALL_DEVICE_GRAPH=1 VORBALL_DEVICE_CLEARANCE=1 channels "pocl_gpuhost$t" 2 "$t" --device cpu
    for ext in csv pdb st; do
        cmp -s seq.$ext pocl_gpuhost$t.$ext ||
            fail "device clearances, $t threads: pocl_gpuhost$t.$ext differs from the reference"
    done
done
for dg in 0 1; do
    VORBALL_DEVICE_GRAPH=$dg run 0 "grm$dg.log" "$vorball" channels "$corpus/data/1grm_single_hole2.pdb" \
        --grid 64 --device cpu -o "grm$dg.csv" --centerlines "grm$dg.pdb"
done
run 0 grmref.log "$vorball" channels "$corpus/data/1grm_single_hole2.pdb" --grid 64 --device ref \
    -o grmref.csv --centerlines grmref.pdb
for f in grm0 grm1; do
    cmp -s grmref.csv $f.csv && cmp -s grmref.pdb $f.pdb || fail "1grm: $f differs from the reference"
done

# The analysis on threads (components, their clearances, the voxel graph on
# slices of at least 4096 voxels): 1chb at grid 128 has about 17,000 channel
# voxels, so three threads link three slices; the same bytes as one thread.
# From 4 threads the bottlenecks' refinement runs beside the pore's search
# (vbc_pore_stage): 5 threads too, and adk_open, whose search reaches the
# through channel's candidate (it waits for the refinement there).
for t in 1 3 5; do
    VORBALL_THREADS=$t run 0 "chb$t.log" "$vorball" channels "$corpus/data/1chb_hole2.pdb" --grid 128 \
        --device ref --centerlines "chb$t.pdb" --json -o "chb$t.json"
    grep -v '"ms"\|"clock"' "chb$t.json" > "chb$t.sj"
done
[ "$(grep -o '"channel_voxels": [0-9]*' chb1.json | grep -o '[0-9]*$')" -ge 12288 ] ||
    fail "1chb grid 128: fewer than 12288 channel voxels, the slices are not exercised"
for ext in pdb sj; do
    for t in 3 5; do
        cmp -s chb1.$ext chb$t.$ext || fail "1chb: chb$t.$ext ($t threads) differs from chb1.$ext (1 thread)"
    done
done
# From 4 threads the analysis runs beside the pore stage (vbc_frame_analyse):
# its time within the pore's span is "beside" (0 below 4 threads), and the
# frame's total is the pipe's span (upload, jfa, masks and the packing,
# about 0.3 ms here) + analysis + pore - beside: above the sum of the keys
# less beside (3 decimals a key), by less than beside itself.
ms_check() { # file threads
    grep -o '"ms": {[^}]*}' "$1" | head -1 | tr -d '"{}' | tr ',' '\n' | awk -F': *' -v t="$2" '
        { gsub(/ /, "", $1); v[$1] = $2 }
        END {
            if (!("beside" in v)) { print "no beside key"; exit 1 }
            b = v["beside"]
            if (t >= 4 && !(b > 0 && b <= v["analysis"] + 0.001)) { print "beside " b; exit 1 }
            if (t < 4 && b != 0) { print "beside " b " on " t " threads"; exit 1 }
            e = v["total"] - (v["upload"] + v["jfa"] + v["masks"] + v["analysis"] + v["pore"] - b)
            if (e < -0.003 || (t >= 4 && e >= b)) { print "total " v["total"] ", beside " b ", off by " e; exit 1 }
        }' || fail "$1: the ms clocks ($2 threads)"
}
ms_check chb1.json 1
ms_check chb5.json 5
for t in 1 5; do
    VORBALL_THREADS=$t run 0 "adk$t.log" "$vorball" channels "$corpus/data/adk_open.pdb.gz" \
        --device ref --centerlines "adk$t.pdb" --json -o "adk$t.json"
    grep -v '"ms"\|"clock"' "adk$t.json" > "adk$t.sj"
done
for ext in pdb sj; do
    cmp -s adk1.$ext adk5.$ext || fail "adk_open: adk5.$ext (5 threads) differs from adk1.$ext (1 thread)"
done
ms_check adk5.json 5

# From 4 threads a frame in analysis runs its analysis beside its pore stage
# once the pore request is fixed (--axis: from the second frame on), on one
# and on three frames in analysis at once: the sequential loop's bytes.
channels axseq 0 2 --device ref --axis 0,0,1
for w in 1 3; do
    export VORBALL_FRAMES_IN_FLIGHT=$w
    channels "ax${w}t5" 2 5 --device ref --axis 0,0,1
    same axseq "ax${w}t5"
done
export VORBALL_FRAMES_IN_FLIGHT=1
VORBALL_THREADS=5 run 0 axj.log "$vorball" channels "$top" --traj "$xtc" --grid 64 --device ref \
    --axis 0,0,1 --json -o axj.json
[ "$(grep -o '"beside": [0-9.]*' axj.json | grep -vc ' 0\.000$')" -ge 5 ] ||
    fail "axj.json: fewer than 5 frames ran the analysis beside the pore stage"

# Four frames in analysis at once on 5 threads: every frame runs its
# analysis beside its pore stage, those taken in before the first frame's
# back half fixed the request (--axis) as the later ones (they wait for it),
# and without a fixed request (this trajectory has no pore along a found
# axis) each frame once the frames before it are out (vbc_run_gate): the
# sequential loop's JSON less its clocks, the same with the overlap off
# (VORBALL_ANALYSIS_BESIDE=0) and on PoCL; ms.beside above 0 in each of the
# 10 frames, 0 in each with the overlap off.
bjson() { # NAME WIDTH AHEAD BESIDE DEVICE ARGS...
    name=$1
    VORBALL_FRAMES_IN_FLIGHT=$2 VORBALL_FRAMES_AHEAD=$3 VORBALL_ANALYSIS_BESIDE=$4 VORBALL_THREADS=5 \
        run 0 "$name.log" "$vorball" channels "$top" --traj "$xtc" --grid 64 --device "$5" --json \
        -o "$name.json" $6
    grep -v '"ms"\|"clock"\|"device"' "$name.json" > "$name.sj"
}
besides() { # NAME: the frames whose ms.beside is above 0
    grep -o '"beside": [0-9.]*' "$1.json" | grep -vc ' 0\.000$'
}
for ax in free z; do
    a=; [ $ax = z ] && a="--axis 0,0,1"
    bjson "b${ax}_seq" 1 0 0 ref "$a"
    bjson "b${ax}_w4" 4 2 1 ref "$a"
    bjson "b${ax}_w4off" 4 2 0 ref "$a"
    for n in w4 w4off; do
        cmp -s "b${ax}_seq.sj" "b${ax}_$n.sj" || fail "b${ax}_$n.json differs from the sequential loop's"
    done
    [ "$(besides "b${ax}_w4")" -eq 10 ] ||
        fail "b${ax}_w4.json: $(besides "b${ax}_w4") of 10 frames ran the analysis beside the pore stage"
    [ "$(besides "b${ax}_w4off")" -eq 0 ] || fail "b${ax}_w4off.json: the analysis beside with it off"
done
grep -q '"axis_from"' bfree_seq.json && fail "bfree_seq.json: a pore (the no-pore case is not exercised)"
grep -q '"axis_from"' bz_seq.json || fail "bz_seq.json: no pore along --axis"
bjson bz_pocl 4 2 1 cpu "--axis 0,0,1"
cmp -s bz_seq.sj bz_pocl.sj || fail "bz_pocl.json (PoCL, 4 in flight) differs from the sequential reference"
[ "$(besides bz_pocl)" -eq 10 ] || fail "bz_pocl.json: $(besides bz_pocl) of 10 frames beside"

# --fixed-grid: the reader fits the grid on the first frame it runs.
channels fix0 0 2 --device ref --fixed-grid --frames 2:10:3
channels fix2 2 2 --device ref --fixed-grid --frames 2:10:3
same fix0 fix2
[ "$(tail -n +2 fix2.stats | cut -d, -f4,5 | sort -u | wc -l)" -eq 1 ] || fail "--fixed-grid: the grid changed"

# A selection: frames 1, 5, 9.
channels sel0 0 2 --device ref --frames 1:10:4
channels sel2 2 2 --device ref --frames 1:10:4
same sel0 sel2
[ "$(tail -n +2 sel2.stats | cut -d, -f1 | tr '\n' ' ')" = "1 5 9 " ] ||
    fail "sel2.stats: frames $(tail -n +2 sel2.stats | cut -d, -f1 | tr '\n' ' '), expected 1 5 9"

# JSON, its clocks left out.
for d in 0 3; do
    VORBALL_FRAMES_AHEAD=$d run 0 "j$d.log" "$vorball" channels "$top" --traj "$xtc" --grid 64 \
        --device ref --json -o "j$d.json"
    grep -v '"ms"\|"clock"\|"device"' "j$d.json" > "j$d.sj"
done
[ "$(grep -c '"frame"' j0.sj)" -eq 10 ] || fail "j0.json: $(grep -c '"frame"' j0.sj) frames, expected 10"
cmp -s j0.sj j3.sj || fail "JSON in flight differs from the sequential JSON"

# A trajectory cut inside its sixth frame: the same failure, no table.
size=$(wc -c < "$xtc")
head -c $((size * 55 / 100)) "$xtc" > cut.xtc
for d in 0 2; do
    VORBALL_FRAMES_AHEAD=$d "$vorball" channels "$top" --traj cut.xtc --grid 64 --device ref \
        -o "cut$d.csv" > "cut$d.log" 2>&1
    echo $? > "cut$d.rc"
    [ -e "cut$d.csv" ] && fail "cut$d.csv written after a failure"
    grep -o 'E[0-9][0-9]*' "cut$d.log" | head -1 > "cut$d.e"
done
[ "$(cat cut0.rc)" -ne 0 ] || fail "a cut trajectory exited 0"
cmp -s cut0.rc cut2.rc || fail "cut trajectory: exit $(cat cut2.rc) in flight, $(cat cut0.rc) sequential"
cmp -s cut0.e cut2.e || fail "cut trajectory: $(cat cut2.e) in flight, $(cat cut0.e) sequential"
[ -s cut0.e ] || fail "cut trajectory: no numbered error"
cmp -s cut0.log cut2.log || fail "cut trajectory: stderr in flight differs from the sequential one"

# The writer fails on the first frame (a volume in no folder) while the
# reader is frames ahead: the same exit and stderr, no table, no hang.
for d in 0 8; do
    VORBALL_FRAMES_AHEAD=$d "$vorball" channels "$top" --traj "$xtc" --grid 32 --device ref \
        --volume "nofolder/v%d.mrc" -o "vol$d.csv" > "vol$d.log" 2>&1
    echo $? > "vol$d.rc"
    [ -e "vol$d.csv" ] && fail "vol$d.csv written after a failure"
done
[ "$(cat vol0.rc)" -ne 0 ] || fail "a volume in no folder exited 0"
cmp -s vol0.rc vol8.rc && cmp -s vol0.log vol8.log || fail "writer failure: in flight differs from sequential"
exit 0
