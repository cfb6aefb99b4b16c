#!/bin/sh
# `vorball channels` over a 51-model trajectory under mpirun -np 1, 2 and 3:
# the table (CSV and JSON), the per-frame statistics and the centrelines
# are one process's bytes, timing columns aside; volumes per frame ('%d')
# and the picture of the first frame are the same files.
# usage: channels.sh VORBALL MPIEXEC CORPUS_DIR WORK_DIR
vorball=$1 mpiexec=$2 corpus=$3 work=$4/mpi_channels
here=$(cd "$(dirname "$0")" && pwd)
. "$here/mpi_lib.sh"
mkdir -p "$work" || fail "cannot create $work"
trj=$corpus/data/ngl_md_ascii_trj.pdb
# 26 frames: on 2 ranks two rounds (16 + 10 frames), on 3 a round of 24 and
# one of 2 that leaves rank 2 without a frame.
opts="--grid 32 --frames ::2 --device ref --no-pore"
untimed() { # the statistics without their timing columns
    cut -d, -f1-12 "$1"
}
unms() { # JSON without the per-frame timings (the "ms" and "clock" objects)
    sed 's/"ms": {[^}]*}//; s/"clock": {[^}]*}//' "$1"
}
run 0 "$work/c.1.err" "$vorball" channels $opts "$trj" -o "$work/c.1.csv" --stats-file "$work/s.1.csv" \
    --centerlines "$work/cl.1.pdb" --volume "$work/v.1.%d.mrc" --png "$work/p.1.png"
run 0 "$work/j.1.err" "$vorball" channels $opts "$trj" --json -o "$work/j.1.json"
n=$(grep -c '^[0-9]' "$work/s.1.csv")
[ "$n" -eq 26 ] || fail "expected 26 frames in the statistics, got $n"
# mpirun -np 1 is one process: the same table.
run 0 "$work/c.np1.err" mpi 1 "$vorball" channels $opts "$trj" -o "$work/c.np1.csv"
same_bytes "table on 1 rank" "$work/c.1.csv" "$work/c.np1.csv"
for np in 2 3; do
    run 0 "$work/c.$np.err" mpi $np "$vorball" channels $opts "$trj" -o "$work/c.$np.csv" \
        --stats-file "$work/s.$np.csv" --centerlines "$work/cl.$np.pdb" --volume "$work/v.$np.%d.mrc" \
        --png "$work/p.$np.png"
    same_bytes "table on $np ranks" "$work/c.1.csv" "$work/c.$np.csv"
    same_bytes "centrelines on $np ranks" "$work/cl.1.pdb" "$work/cl.$np.pdb"
    untimed "$work/s.1.csv" > "$work/s.1.cut"
    untimed "$work/s.$np.csv" > "$work/s.$np.cut"
    same_bytes "statistics on $np ranks" "$work/s.1.cut" "$work/s.$np.cut"
    for f in $(seq 0 2 50); do
        same_bytes "volume of frame $f on $np ranks" "$work/v.1.$f.mrc" "$work/v.$np.$f.mrc"
    done
    same_bytes "picture on $np ranks" "$work/p.1.png" "$work/p.$np.png"
    expect_line "$work/c.$np.err" "^vorball channels: 26 frame\(s\), 26 run\(s\) on $np ranks"
    run 0 "$work/j.$np.err" mpi $np "$vorball" channels $opts "$trj" --json -o "$work/j.$np.json"
    unms "$work/j.1.json" > "$work/j.1.cut"
    unms "$work/j.$np.json" > "$work/j.$np.cut"
    same_bytes "JSON on $np ranks" "$work/j.1.cut" "$work/j.$np.cut"
done
# Frames in analysis at once (VORBALL_FRAMES_IN_FLIGHT, issue 33) on one
# process, and asked of 2 ranks (each runs its frames one at a time): the
# bytes of the run above.
VORBALL_FRAMES_IN_FLIGHT=4 VORBALL_FRAMES_AHEAD=0 run 0 "$work/c.w4.err" "$vorball" channels $opts "$trj" \
    -o "$work/c.w4.csv"
same_bytes "table with 4 frames in flight" "$work/c.1.csv" "$work/c.w4.csv"
VORBALL_FRAMES_IN_FLIGHT=4 run 0 "$work/c.w4np2.err" mpi 2 "$vorball" channels $opts "$trj" \
    -o "$work/c.w4np2.csv"
same_bytes "table with 4 frames in flight asked of 2 ranks" "$work/c.1.csv" "$work/c.w4np2.csv"
# The pore (default): later frames sweep the first frame's axis, which every
# rank finds itself; the table is one process's.
popts="--grid 32 --frames ::2 --device ref"
run 0 "$work/pore.1.err" "$vorball" channels $popts "$trj" -o "$work/pore.1.csv"
# Since the pore verdict (issue 32) this peptide gets W808 (its path is not
# walled by its atoms for 15 A): the sweep still runs on every rank, and the
# table (no pore row) and the verdict must be one process's.
grep -q '^0,1,1,pore,' "$work/pore.1.csv" || grep -q "W808" "$work/pore.1.err" ||
    fail "first frame: neither a pore row nor the W808 verdict"
for np in 2 3; do
    run 0 "$work/pore.$np.err" mpi $np "$vorball" channels $popts "$trj" -o "$work/pore.$np.csv"
    same_bytes "pore table on $np ranks" "$work/pore.1.csv" "$work/pore.$np.csv"
done
# The outputs gathered over every frame run on one process only.
run 2 "$work/prof.err" mpi 2 "$vorball" channels $popts "$trj" -o "$work/prof.csv" --profile "$work/prof.prof.csv"
expect_line "$work/prof.err" "E151: --profile, --plot, --fixed-grid, --occupancy, --html and --atoms run on one process only"
[ ! -e "$work/prof.csv" ] || fail "a refused channels job left $work/prof.csv"
[ ! -e "$work/prof.prof.csv" ] || fail "a refused channels job left $work/prof.prof.csv"
echo "ok: channels of 26 frames on 1, 2 and 3 ranks are one process's output"
