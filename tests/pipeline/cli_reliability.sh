#!/bin/sh
# Command-line failures found by a hostile test (issue 28), each a numbered
# error naming the right file, and no partial output:
#  - `vertices - -o IN < IN` would replace the file stdin reads: E7;
#  - option errors carry their number (E7), as every error does;
#  - a failed write of the vertices names the file (E8);
#  - `channels --volume v%d.mrc` writes a file per frame for any number of
#    frames (the output table held 32: E8 "too many output files" at 31),
#    and none when a later one cannot be written;
#  - a DCD cut inside its first frame: E111 names the DCD, not the topology;
#  - --png p.jpg writes PNG data: W783 says so.
# usage: cli_reliability.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/cli_reliability
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt

# stdin is the output file: refused, the file left as it was.
cp "$corpus/inputs/cubic_lattice.xyzr" in.xyzr
cp in.xyzr in.orig
run 2 "$out" "$vorball" vertices --device ref - -o in.xyzr < in.xyzr
expect_line "$out" "^vorball: E7: in.xyzr: output is the file standard input reads"
cmp -s in.xyzr in.orig || fail "stdin's file was changed"
# stdin from another file into an output: fine.
run 0 "$out" "$vorball" vertices --device ref - -o v.tsv < in.xyzr
expect_line v.tsv "^0,1,3,4,9,10,12,13	0.5	0.5	0.5	"

# Option errors: E7, exit 2.
run 2 "$out" "$vorball" vertices --bogus in.xyzr
expect_line "$out" "^vorball vertices: E7: unknown option '--bogus'"
run 2 "$out" "$vorball" channels --grid 0 in.xyzr
expect_line "$out" "^vorball channels: E7: --grid needs"
run 2 "$out" "$vorball" frobnicate
expect_line "$out" "^vorball: E7: unknown command 'frobnicate'"

# A write that fails names the file.
if [ -w /dev/full ]; then
    run 3 "$out" "$vorball" vertices --device ref "$corpus/data/1crn.pdb" -o /dev/full
    expect_line "$out" "^vorball: E8: /dev/full: "
    "$vorball" vertices --device ref "$corpus/data/1crn.pdb" > /dev/full 2> "$out"
    [ $? -eq 3 ] || fail "vertices > /dev/full: exit not 3"
    expect_line "$out" "^vorball: E8: <stdout>: "
fi

# 51 frames, one volume each.
traj=$corpus/data/ngl_md_ascii_trj.pdb
run 0 "$out" "$vorball" channels --device ref --grid 16 --no-pore --volume "v%d.mrc" -o ch.csv "$traj"
[ "$(ls v*.mrc | wc -l)" -eq 51 ] || fail "not 51 volume files: $(ls v*.mrc | wc -l)"
[ -s v0.mrc ] && [ -s v50.mrc ] || fail "v0.mrc or v50.mrc missing or empty"
cmp -s v0.mrc v50.mrc && fail "v0.mrc and v50.mrc are the same bytes (one frame written twice)"
# One that cannot be written (a folder in its place): E8, and no file at all.
rm -f v*.mrc ch.csv
mkdir v40.mrc
run 3 "$out" "$vorball" channels --device ref --grid 16 --no-pore --volume "v%d.mrc" -o ch.csv "$traj"
expect_line "$out" "E8: v40.mrc"
[ "$(ls -d v*.mrc)" = "v40.mrc" ] || fail "partial output: $(ls -d v*.mrc | head -3)"
[ -e ch.csv ] && fail "partial output: ch.csv"
ls -a | grep -q vorball- && fail "temporary files left: $(ls -a | grep vorball-)"

# A DCD with no whole frame (cut inside frame 1; W801 says so): E111 on it.
dcd=$corpus/data/adk_dims_2frames.dcd
head -c $(( $(wc -c < "$dcd") / 2 )) "$dcd" > cut.dcd
run 21 "$out" "$vorball" channels --device ref --grid 16 --no-pore --dcd cut.dcd "$corpus/data/adk_natom.psf.gz"
expect_line "$out" "^vorball: E111: cut.dcd: no whole frame"

# --png under another image format's name: written, with W783; .png silent.
run 0 "$out" "$vorball" jfa --device ref -n 64 -k 20 --png p.jpg
expect_line "$out" "^vorball: W783: p.jpg: named '.jpg', but --png writes PNG data"
[ "$(head -c 4 p.jpg | tail -c 3)" = "PNG" ] || fail "p.jpg holds no PNG data"
run 0 "$out" "$vorball" jfa --device ref -n 64 -k 20 --png p.png
grep -q W783 "$out" && fail "W783 on a .png name"
echo "cli_reliability: ok"
