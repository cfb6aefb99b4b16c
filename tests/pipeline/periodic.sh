#!/bin/sh
# Periodic boxes (issue 34): `vorball vertices --periodic` against open runs
# of replicated copies (periodic_check.py: an fcc unit cell against the
# central cell of its 5x5x5 copy; 40 random balls in an orthorhombic and in
# a triclinic box against their 3x3x3 copies), the same bytes on the
# reference backend and PoCL and on 1 and 2 threads, the boxes of GRO and
# PDB CRYST1 equal to --box, and the refusals (E120, E135).
# usage: periodic.sh VORBALL WORK_DIR
vorball=$1 work=$2/periodic
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
check=$here/periodic_check.py
for case in fcc random triclinic; do
    python3 "$check" gen $case . || fail "$case: generator"
    box=$(cat $case.box)
    # shellcheck disable=SC2086
    run 0 $case.periodic.err "$vorball" vertices --periodic --box $box --device ref \
        $case.xyzr -o $case.periodic.tsv
    run 0 $case.block.err "$vorball" vertices --device ref $case.block.xyzr -o $case.block.tsv
    expect_line $case.periodic.tsv '^# complete: [0-9]+ certified vertices of the periodic diagram'
    python3 "$check" cmp $case . || exit 1
    # The same bytes on PoCL (the cover's OpenCL kernels) and on 1 thread.
    # shellcheck disable=SC2086
    run 0 $case.cpu.err "$vorball" vertices --periodic --box $box --device cpu $case.xyzr \
        -o $case.cpu.tsv
    cmp -s $case.periodic.tsv $case.cpu.tsv || fail "$case: --device cpu differs from ref"
    # shellcheck disable=SC2086
    run 0 $case.t1.err "$vorball" vertices --periodic --box $box --device ref --threads 1 \
        $case.xyzr -o $case.t1.tsv
    cmp -s $case.periodic.tsv $case.t1.tsv || fail "$case: --threads 1 differs"
done
echo "ok: periodic vertices equal the replicated open runs, same bytes on ref, cpu, 1 thread"

# The json writer: the same members and doubles as the tsv.
run 0 json.err "$vorball" vertices --box 4 4 4 --output-format json --device ref fcc.xyzr \
    -o fcc.json
python3 - <<'PY' || fail "json differs from tsv"
import json
d = json.load(open("fcc.json"))
rows = [l.rstrip("\n").split("\t") for l in open("fcc.periodic.tsv") if not l.startswith("#")]
assert d["comment"].startswith("periodic: box a = (4 0 0)")
assert [",".join(v["ids"]) for v in d["vertices"]] == [r[0] for r in rows]
assert [[v[k] for k in "xyzt"] for v in d["vertices"]] == [[float(c) for c in r[1:5]] for r in rows]
PY

# The box of a GRO file (nm, its last line, here triclinic) and of a PDB
# CRYST1 record (lengths and right angles) are the boxes of --box.
cat > box.gro <<'GRO'
water box cut
 6
    1SOL     OW    1   0.126   0.163   0.112
    1SOL    HW1    2   0.190   0.094   0.093
    2SOL     OW    3   0.501   0.410   0.330
    2SOL    HW1    4   0.580   0.460   0.301
    3SOL     OW    5   0.300   0.601   0.612
    3SOL    HW1    6   0.248   0.650   0.550
   0.80000   0.75000   0.70000   0.00000   0.00000   0.10000   0.00000   0.05000  -0.05000
GRO
run 0 gro.err "$vorball" vertices --periodic --water --device ref box.gro -o gro.tsv
run 0 grobox.err "$vorball" vertices --box 8 0 0 1 7.5 0 0.5 -0.5 7 --water --device ref box.gro \
    -o grobox.tsv
# (other options: all but the provenance lines the same)
sans_provenance gro.tsv > gro.body
sans_provenance grobox.tsv | cmp -s - gro.body || fail "the GRO box differs from --box"
expect_line gro.tsv '^# periodic: box a = \(8 0 0\), b = \(1 7.5 0\), c = \(0.5 -0.5 7\)'
{
    echo "CRYST1   12.000   11.000   10.500  90.00  90.00  90.00 P 1           1"
    i=1
    for xyz in " 1.000   1.500   2.000" " 4.000   5.500   2.500" " 8.000   2.000   7.000" \
               " 2.500   8.500   6.000" " 9.500   9.000   1.500" " 6.000   4.000   9.000"; do
        set -- $xyz
        printf 'ATOM  %5d  O   HOH A%4d    %8.3f%8.3f%8.3f  1.00  0.00           O\n' $i $i $1 $2 $3
        i=$((i + 1))
    done
    echo END
} > box.pdb
run 0 pdb.err "$vorball" vertices --periodic --water --device ref box.pdb -o pdb.tsv
run 0 pdbbox.err "$vorball" vertices --box 12 11 10.5 --water --device ref box.pdb -o pdbbox.tsv
sans_provenance pdb.tsv > pdb.body
sans_provenance pdbbox.tsv | cmp -s - pdb.body || fail "the CRYST1 box differs from --box"
echo "ok: GRO and CRYST1 boxes read exactly"

# Refusals: no box (E120, exit 30), a box too small for its atoms (E135,
# exit 45), a --box of 4 numbers (usage, exit 2); no output file left.
run 30 nobox.err "$vorball" vertices --periodic fcc.xyzr -o nobox.tsv
expect_line nobox.err 'E120'
[ ! -e nobox.tsv ] || fail "E120 left an output file"
printf '1 1 0.1 0.1\n5 2 0.2 0.1\n3 7 0.3 0.1\n8 6 0.1 0.1\n' > flat.xyzr
run 45 small.err "$vorball" vertices --box 10 10 0.5 flat.xyzr -o small.tsv
expect_line small.err 'E135'
[ ! -e small.tsv ] || fail "E135 left an output file"
run 2 count.err "$vorball" vertices --box 4 4 4 4 fcc.xyzr
echo "ok: E120, E135 and a bad --box refused"

# verify --periodic: the files above certified line by line; planted faults
# found with their line (a translate that is not canonical, a moved point,
# a repeated line, a member swapped for another atom's image), exit 1.
box=$(cat triclinic.box)
# shellcheck disable=SC2086
run 0 verify.out "$vorball" verify --periodic --box $box triclinic.xyzr triclinic.periodic.tsv
expect_line verify.out '271 periodic vertex lines: 271 certified, 0 not canonical'
python3 - <<'PY' || fail "planting faults"
lines = open("triclinic.periodic.tsv").read().splitlines(True)
head = [l for l in lines if l.startswith("#")]
body = [l for l in lines if not l.startswith("#")]
def members(l):
    return l.split("\t")[0].replace("),", ")\n").split("\n")
def shifted(l):
    ids, rest = l.split("\t", 1)
    out = []
    for m in members(l):
        i, s = m.split("@")
        d = [int(c) for c in s.strip("()").split(",")]
        out.append("%s@(%d,%d,%d)" % (i, d[0] + 1, d[1], d[2]))
    return ",".join(out) + "\t" + rest
def moved(l):
    cols = l.split("\t")
    cols[1] = repr(float(cols[1]) + 0.01)
    return "\t".join(cols)
def swapped(l):
    ids, rest = l.split("\t", 1)
    ms = members(l)
    i, s = ms[-1].split("@")
    ms[-1] = "%d@%s" % ((int(i) + 1) % 40, s)
    return ",".join(sorted(ms, key=lambda m: (int(m.split("@")[0]), m))) + "\t" + rest
for name, f in (("noncanonical", shifted), ("moved", moved), ("swapped", swapped)):
    open("fault_%s.tsv" % name, "w").write("".join(head + [f(body[0])] + body[1:]))
open("fault_duplicate.tsv", "w").write("".join(head + body + body[5:6]))
PY
for fault in noncanonical moved swapped duplicate; do
    # shellcheck disable=SC2086
    run 1 verify_$fault.out "$vorball" verify --periodic --box $box triclinic.xyzr fault_$fault.tsv
done
# The first vertex line follows the header (title, provenance, certificate,
# columns: 7 lines); the duplicate is the 272nd vertex line.
first=$(($(grep -c '^#' triclinic.periodic.tsv) + 1))
[ "$first" -eq 8 ] || fail "the periodic header is not 7 lines"
expect_line verify_noncanonical.out "fault_noncanonical.tsv:$first: not canonical"
expect_line verify_moved.out "fault_moved.tsv:$first: wrong coordinates"
expect_line verify_swapped.out "fault_swapped.tsv:$first: not a vertex"
expect_line verify_duplicate.out "fault_duplicate.tsv:$((first + 271)): duplicate"
echo "ok: verify --periodic certifies the files and finds planted faults"

# Frames of a trajectory, each in its own box (XTC box vectors per frame):
# one tsv, a '# frame K' block per frame, the box of MDAnalysis' reading.
data=$here/../../corpus/data
run 0 traj.err "$vorball" vertices --water --device ref --traj "$data/ngl_md_10frames.xtc" \
    --frames 0:2 "$data/ngl_md_ascii_trj.pdb" -o traj.tsv
[ "$(grep -c '^# frame ' traj.tsv)" -eq 2 ] || fail "--traj --frames 0:2: not 2 frames"
expect_line traj.tsv '^# periodic: box a = \(56.064 0 0\), b = \(0 56.064 0\), c = \(0 0 56.064\)'
expect_line traj.tsv '^# periodic: box a = \(56.035 0 0\)'
run 2 traj_json.err "$vorball" vertices --traj "$data/ngl_md_10frames.xtc" --output-format json \
    "$data/ngl_md_ascii_trj.pdb" -o traj.json
echo "ok: vertices --traj: every frame periodic in its own box"

# Cell measures frame by frame, periodic (each model in the CRYST1 written
# before its MODEL): one table with a frame column; the volumes of a probe
# that covers each box sum to that box's volume.
awk 'BEGIN {
    for (k = 0; k < 3; k++) {
        e = 5 + 0.5 * k
        printf "CRYST1%9.3f%9.3f%9.3f  90.00  90.00  90.00 P 1           1\n", e, e, e
        printf "MODEL     %4d\n", k + 1
        printf "ATOM      1  C   GLY A   1    %8.3f%8.3f%8.3f  1.00  0.00           C\n", 1 + 0.1 * k, 1.25, 0.5
        printf "ATOM      2  C   GLY A   1    %8.3f%8.3f%8.3f  1.00  0.00           C\n", 3.5, 2.75 - 0.2 * k, 3 + 0.1 * k
        print "ENDMDL"
    } }' > models.pdb
run 0 cells_frames.err "$vorball" cells --periodic --frames 0:3:1 --probe 4 --max-patches 4000 \
    models.pdb -o cells_frames.tsv
awk -F'\t' '!/^#/ && $1 != "frame" { v[$1] += $7 }
    END { exit !(length(v) == 3 && v[0] > 124.7 && v[0] < 125.3 && v[1] > 166.1 && v[1] < 166.7 &&
                 v[2] > 215.7 && v[2] < 216.3) }' cells_frames.tsv ||
    fail "cells --periodic --frames: the frames' volumes are not their boxes' 125, 166.375, 216"
echo "ok: cells --periodic --frames: every frame in its own box"
