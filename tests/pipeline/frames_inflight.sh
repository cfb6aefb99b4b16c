#!/bin/sh
# Issue 33: frames in analysis at once (VORBALL_FRAMES_IN_FLIGHT, vbc_flight.h)
# against the sequential loop (VORBALL_FRAMES_AHEAD=0, one frame in flight):
# every output of every frame (table, statistics, centrelines, profile, JSON
# less its clocks, per-frame volumes, the occupancy) and stderr less the
# closing timing line must be the same bytes for 1, 2 and 4 frames in
# analysis x 1 and 2 threads x 0 and 2 frames ahead, on the 51-model MD PDB
# and on its 10-frame XTC, and with MDA set (a folder holding MDAnalysis'
# adk_oplsaa.gro + .xtc, 47,681 atoms; GPL-2+, not in the repository) on its
# first 3 frames. A failure injected in the analysis of a middle frame
# (VORBALL_TEST_FAIL_FRAME) and a trajectory cut inside a frame give the same
# exit, the same stderr and no table, statistics or JSON, at every width. A
# memory budget too small for the frames in flight is E127 (exit 37), no table.
# usage: frames_inflight.sh VORBALL CORPUS WORKDIR [MDA]
vorball=$1 corpus=$2 work=$3 mda=${4:-}
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/frames_inflight"
top="$corpus/data/ngl_md_ascii_trj.pdb" xtc="$corpus/data/ngl_md_10frames.xtc"

# channels NAME WIDTH THREADS AHEAD INPUT... : one run, its outputs NAME.*,
# its stderr less the closing timing line in NAME.err.
channels() {
    name=$1 width=$2 threads=$3 ahead=$4
    shift 4
    VORBALL_FRAMES_IN_FLIGHT=$width VORBALL_THREADS=$threads VORBALL_FRAMES_AHEAD=$ahead \
        run 0 "$name.log" "$vorball" channels "$@" -o "$name.csv" --centerlines "$name.pdb" \
        --stats-file "$name.stats" --profile "$name.prof" --volume "$name.v%d.mrc"
    grep -v '^vorball channels: [0-9]* frame' "$name.log" > "$name.err"
    cut -d, -f1-12,18-24 "$name.stats" > "$name.st"
    VORBALL_FRAMES_IN_FLIGHT=$width VORBALL_THREADS=$threads VORBALL_FRAMES_AHEAD=$ahead \
        run 0 "$name.jlog" "$vorball" channels "$@" --json -o "$name.json"
    grep -v '"ms"\|"clock"\|"device"' "$name.json" > "$name.sj"
}

# same REF NAME: every output of NAME the bytes of REF's.
same() {
    for ext in csv pdb st prof sj err; do
        cmp -s "$1.$ext" "$2.$ext" || { diff "$1.$ext" "$2.$ext" | head -20 >&2; fail "$2.$ext differs from $1.$ext"; }
    done
    n=0
    for v in "$1".v*.mrc; do
        cmp -s "$v" "$2${v#"$1"}" || fail "$2${v#"$1"} differs from $v"
        n=$((n + 1))
    done
    [ "$n" -ge 1 ] || fail "$1: no per-frame volume"
}

# matrix TAG INPUT...: the reference and the 12 combinations.
matrix() {
    tag=$1
    shift
    channels "${tag}_ref" 1 2 0 "$@"
    for w in 1 2 4; do
        for t in 1 2; do
            for a in 0 2; do
                channels "${tag}_w${w}t${t}a$a" "$w" "$t" "$a" "$@"
                same "${tag}_ref" "${tag}_w${w}t${t}a$a"
            done
        done
    done
}

# The 51-model PDB, frames 0 to 11, with a fixed grid and the occupancy.
matrix pdb "$top" --grid 64 --device ref --frames 0:12
[ "$(tail -n +2 pdb_ref.stats | wc -l)" -eq 12 ] || fail "pdb_ref.stats: not 12 frames"
[ "$(ls pdb_ref.v*.mrc | wc -l)" -eq 12 ] || fail "pdb_ref: not 12 volumes"
# The 10-frame XTC: every frame, 4 channels rows at least, the plot's series.
matrix xtc "$top" --traj "$xtc" --grid 64 --device ref
[ "$(tail -n +2 xtc_ref.stats | cut -d, -f1 | tr '\n' ' ')" = "0 1 2 3 4 5 6 7 8 9 " ] ||
    fail "xtc_ref.stats: frames $(tail -n +2 xtc_ref.stats | cut -d, -f1 | tr '\n' ' ')"
# The JSON's run clock: 10 frames, a positive frame rate.
python3 - xtc_w4t2a2.json <<'PY' || fail "xtc_w4t2a2.json: no run clock"
import json, sys
c = json.load(open(sys.argv[1]))["clock"]
assert c["frames"] == 10 and c["fps"] > 0 and c["wall"] > 0 and c["cpu"] > 0, c
PY
# The occupancy (--fixed-grid) sums every frame's flags in frame order.
for w in 1 4; do
    VORBALL_FRAMES_IN_FLIGHT=$w VORBALL_FRAMES_AHEAD=$((w > 1 ? 2 : 0)) run 0 "occ$w.log" "$vorball" \
        channels "$top" --traj "$xtc" --grid 32 --device ref --fixed-grid --occupancy "occ$w.mrc" \
        -o "occ$w.csv"
done
cmp -s occ1.mrc occ4.mrc && cmp -s occ1.csv occ4.csv || fail "--occupancy: 4 in flight differ"

# adk_oplsaa (47,681 atoms, solvated), frames 0 to 2, grid 64.
if [ -n "$mda" ] && [ -f "$mda/adk_oplsaa.gro" ] && [ -f "$mda/adk_oplsaa.xtc" ]; then
    matrix adk "$mda/adk_oplsaa.gro" --traj "$mda/adk_oplsaa.xtc" --grid 64 --device ref --frames 0:3
    [ "$(tail -n +2 adk_ref.stats | wc -l)" -eq 3 ] || fail "adk_ref.stats: not 3 frames"
else
    echo "frames_inflight: no adk_oplsaa in '$mda': the 47k-atom case is not run"
fi

# fails NAME WIDTH AHEAD ARGS...: a run that must fail; its exit, stderr and
# the outputs left.
fails() {
    name=$1 width=$2 ahead=$3
    shift 3
    VORBALL_FRAMES_IN_FLIGHT=$width VORBALL_FRAMES_AHEAD=$ahead "$vorball" channels "$@" \
        -o "$name.csv" --stats-file "$name.stats" --centerlines "$name.pdb" > "$name.log" 2>&1
    echo $? > "$name.rc"
    for ext in csv stats pdb; do
        [ -e "$name.$ext" ] && fail "$name.$ext written after a failure"
    done
    VORBALL_FRAMES_IN_FLIGHT=$width VORBALL_FRAMES_AHEAD=$ahead "$vorball" channels "$@" --json \
        -o "$name.json" > /dev/null 2>&1 && fail "$name: --json exited 0"
    [ -e "$name.json" ] && fail "$name.json written after a failure"
    return 0
}
# same_failure REF NAME
same_failure() {
    [ "$(cat "$1.rc")" -ne 0 ] || fail "$1 exited 0"
    cmp -s "$1.rc" "$2.rc" || fail "$2: exit $(cat "$2.rc"), $(cat "$1.rc") in $1"
    cmp -s "$1.log" "$2.log" || { diff "$1.log" "$2.log" >&2; fail "$2: stderr differs from $1's"; }
}
# The analysis of frame 5 of 10 fails (E6) while frames after it are in flight.
size=$(wc -c < "$xtc")
head -c $((size * 55 / 100)) "$xtc" > cut.xtc
for w in 1 2 4; do
    for a in 0 2; do
        VORBALL_TEST_FAIL_FRAME=5 fails "inj_w${w}a$a" "$w" "$a" "$top" --traj "$xtc" --grid 64 --device ref
        same_failure inj_w1a0 "inj_w${w}a$a"
        fails "cut_w${w}a$a" "$w" "$a" "$top" --traj cut.xtc --grid 64 --device ref
        same_failure cut_w1a0 "cut_w${w}a$a"
    done
done
[ "$(cat inj_w1a0.rc)" -eq 6 ] || fail "injected failure: exit $(cat inj_w1a0.rc), expected 6"
grep -q 'E6: .*failure injected in the analysis of frame 5' inj_w1a0.log || fail "inj_w1a0.log: no E6 of frame 5"
grep -q 'E115' cut_w1a0.log || fail "cut.xtc: no E115"

# A budget too small for 4 frames in flight: E127 (exit 37) before any output;
# with the width left to its default the window shrinks to what fits.
VORBALL_FRAMES_IN_FLIGHT=4 VORBALL_FRAMES_MEMORY=1 "$vorball" channels "$top" --traj "$xtc" --grid 128 \
    --device ref -o mem.csv > mem.log 2>&1
echo $? > mem.rc
[ "$(cat mem.rc)" -eq 37 ] || { cat mem.log >&2; fail "E127: exit $(cat mem.rc), expected 37"; }
grep -q 'E127: .*MiB a frame' mem.log || fail "mem.log: no E127 saying the MiB a frame"
[ -e mem.csv ] && fail "mem.csv written after E127"
exit 0
