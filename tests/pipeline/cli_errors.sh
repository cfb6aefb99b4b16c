#!/bin/sh
# `vorball verify` refuses bad invocations and bad files with the documented
# exit codes: 2 usage, 3 i/o, 10 + detail for input errors.
# usage: cli_errors.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/cli_errors
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
cd "$corpus/inputs" || fail "no $corpus/inputs"
out=$work/out.txt
run 0 "$out" "$vorball" verify --help
expect_line "$out" "^usage: vorball verify SPHERES VERTICES"
run 2 "$out" "$vorball" verify cubic_lattice.xyzr
run 2 "$out" "$vorball" verify cubic_lattice.xyzr ../golden/cubic_lattice.tsv --tol 0
run 2 "$out" "$vorball" verify cubic_lattice.xyzr ../golden/cubic_lattice.tsv --bogus
run 3 "$out" "$vorball" verify cubic_lattice.xyzr "$work/does-not-exist.tsv"
printf '0,1,3,4\t0.5\t0.5\n' > "$work/short.tsv"
run 11 "$out" "$vorball" verify cubic_lattice.xyzr "$work/short.tsv"
expect_line "$out" "E101: .*short.tsv:1: "
printf '0,1,3,4\t0.5\t0.5\tnan\t1\n' > "$work/nan.tsv"
run 12 "$out" "$vorball" verify cubic_lattice.xyzr "$work/nan.tsv"
# the vertex file from stdin, the report to a file
run 0 "$out" "$vorball" verify cubic_lattice.xyzr - -o "$work/report.txt" < ../golden/cubic_lattice.tsv
expect_line "$work/report.txt" "^verify: 8 lines \(tsv\): 8 certified"
# ids beyond the sphere count are not a vertex, not a crash
printf '0,1,3,99\t0.5\t0.5\t0.5\t0.6\n' > "$work/range.tsv"
run 1 "$out" "$vorball" verify cubic_lattice.xyzr "$work/range.tsv"
expect_line "$out" "range.tsv:1: not a vertex: fewer than 4 distinct ids, or an id out of range$"
# an empty vertex file verifies nothing: E105 (exit 15), not success
: > "$work/empty.tsv"
run 15 "$out" "$vorball" verify cubic_lattice.xyzr "$work/empty.tsv"
expect_line "$out" "E105: .*empty.tsv: no vertex lines"
printf '# only a comment\n' > "$work/comment.tsv"
run 15 "$out" "$vorball" verify cubic_lattice.xyzr "$work/comment.tsv"
# a line that names a sphere twice is malformed (E101 naming it), in every format
printf '0,1,3,3\t0.5\t0.5\t0.5\t0.6\n' > "$work/repeat.tsv"
run 11 "$out" "$vorball" verify cubic_lattice.xyzr "$work/repeat.tsv"
expect_line "$out" "E101: .*repeat.tsv:1: sphere 3 is named twice"
printf '0 1 1 3 0.5 0.5 0.5 0.6\n' > "$work/repeat.voronota"
run 11 "$out" "$vorball" verify cubic_lattice.xyzr "$work/repeat.voronota"
expect_line "$out" "E101: .*repeat.voronota:1: "
# a vertex file over 2 GiB is refused before it is read (E110, exit 20); the
# file is sparse, so the test costs no disk
rm -f "$work/huge.tsv"
if truncate -s 2200M "$work/huge.tsv" 2>/dev/null; then
    run 20 "$out" "$vorball" verify cubic_lattice.xyzr "$work/huge.tsv"
    expect_line "$out" "E110: .*huge.tsv: vertex file is larger than"
    rm -f "$work/huge.tsv"
fi
echo "ok: cli errors"
