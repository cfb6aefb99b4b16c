#!/bin/sh
# Output files (issue 18, item 8): an output that is the same file as an
# input (by any name or link) is refused with exit 2 and the input is left
# alone; a command that fails leaves none of its outputs, and a file that was
# there before keeps its bytes; a command that succeeds leaves all of them and
# no temporary file; a link is replaced at its target; SIGTERM removes the
# temporary files of a run it stops.
# usage: outputs.sh VORBALL CORPUS_DIR WORK_DIR
vorball=$1 corpus=$2 work=$3/outputs
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
fresh_dir "$work"
out=$work/out.txt
no_temps() {
    left=$(ls -A | grep 'vorball-' || true)
    [ -z "$left" ] || fail "temporary files left: $left"
}

cp "$corpus/data/1grm_single_hole2.pdb" in.pdb
cp "$corpus/inputs/cubic_lattice.xyzr" in.xyzr
ln -s in.pdb link.pdb
sum=$(cksum < in.pdb)
run 2 "$out" "$vorball" channels --device ref --grid 32 in.pdb -o in.pdb
expect_line "$out" "E7: in.pdb: output is the same file as 'in.pdb' on the command line"
run 2 "$out" "$vorball" channels --device ref --grid 32 in.pdb -o link.pdb
expect_line "$out" "E7: link.pdb: output is the same file as 'in.pdb'"
run 2 "$out" "$vorball" channels --device ref --grid 32 link.pdb -o out.csv --stats-file ./in.pdb
expect_line "$out" "E7: ./in.pdb: output is the same file as 'link.pdb'"
[ "$(cksum < in.pdb)" = "$sum" ] || fail "channels changed its input"
[ ! -e out.csv ] || fail "a refused command left out.csv"
# --plot (issue 32): the PNG is an output like the others, drawn by gnuplot
# (where installed) and in place when the command ends; the script kept
# beside it draws the same name; no temporary file is left.
run 0 "$out" "$vorball" channels --device ref --grid 32 in.pdb -o plot.csv --plot plot.png
if command -v gnuplot > /dev/null 2>&1; then
    [ "$(head -c 4 plot.png | od -An -c | tr -d ' ')" = "211PNG" ] || fail "--plot wrote no PNG"
else
    expect_line "$out" "W807"
fi
grep -q "^set output 'plot.png'$" plot.png.gp || fail "the kept plot script draws another file"
[ -z "$(ls -A | grep 'plot.png.tmp' || true)" ] || fail "--plot left temporary files"
no_temps
# --pymol (issue 32): PyMOL loads a structure with coordinates and the
# trajectory: a PSF topology or a GRO file gets its first frame written
# beside the script as PDB; a trajectory is loaded into the molecule; a PDB
# is loaded as it is.
psf=$corpus/data/adk_natom.psf.gz dcd=$corpus/data/adk_dims_2frames.dcd
run 0 "$out" "$vorball" channels --device ref --grid 16 --no-pore "$psf" --traj "$dcd" \
    --centerlines a.pdb --pymol a.pml -o a.csv
grep -q '^load a.pml.frame0.pdb, molecule$' a.pml || fail "the PyMOL script does not load the first frame"
grep -q "^load_traj .*adk_dims_2frames.dcd, molecule$" a.pml || fail "the PyMOL script does not load the trajectory"
[ "$(grep -c '^ATOM' a.pml.frame0.pdb)" = 3341 ] || fail "a.pml.frame0.pdb does not hold the 3341 atoms"
run 0 "$out" "$vorball" channels --device ref --grid 16 --no-pore "$corpus/data/adk_oplsaa_protein.gro.gz" \
    --centerlines g.pdb --pymol g.pml -o g.csv
grep -q '^load g.pml.frame0.pdb, molecule$' g.pml || fail "the PyMOL script loads the GRO file"
[ -s g.pml.frame0.pdb ] || fail "no first frame for the GRO input"
run 0 "$out" "$vorball" channels --device ref --grid 16 --no-pore in.pdb --centerlines q.pdb --pymol q.pml -o q.csv
grep -q '^load in.pdb, molecule$' q.pml || fail "the PyMOL script does not load the PDB input"
[ ! -e q.pml.frame0.pdb ] || fail "a first frame written for a PDB input"
no_temps
xsum=$(cksum < in.xyzr)
run 2 "$out" "$vorball" vertices --device ref in.xyzr -o "$work/in.xyzr"
run 2 "$out" "$vorball" reference in.xyzr -o in.xyzr
"$vorball" reference in.xyzr -o v.tsv 2> "$out" || fail "reference failed"
vsum=$(cksum < v.tsv)
run 2 "$out" "$vorball" verify in.xyzr v.tsv -o v.tsv
[ "$(cksum < in.xyzr)" = "$xsum" ] || fail "vertices or reference changed its input"
[ "$(cksum < v.tsv)" = "$vsum" ] || fail "verify changed its vertex file"
printf '3 4\n20.5 11\n' > seeds.txt
run 2 "$out" "$vorball" jfa -n 32 --device ref seeds.txt --png seeds.txt -o /dev/null
[ "$(cat seeds.txt)" = "$(printf '3 4\n20.5 11')" ] || fail "jfa --png overwrote its seeds"
no_temps

# Frame 2 of two is malformed: channels fails after writing frame 1, and
# leaves no output; the file that was there keeps its bytes.
{
    echo "MODEL        1"; grep '^ATOM' in.pdb; echo ENDMDL
    echo "MODEL        2"; grep '^ATOM' in.pdb | sed '5s/^\(.\{30\}\)......../\1   x.000/'
    echo ENDMDL
} > two.pdb
echo keep > old.csv
set -- --device ref --grid 32 two.pdb -o old.csv --stats-file s.csv --centerlines c.pdb \
    --pymol p.pml --volume v.mrc --png p.png
run 11 "$out" "$vorball" channels "$@"
expect_line "$out" "E101: two.pdb:272: "
[ "$(cat old.csv)" = keep ] || fail "the failed command changed old.csv"
for f in s.csv c.pdb p.pml v.mrc p.png; do
    [ ! -e $f ] || fail "the failed command left $f"
done
no_temps
# The same with frame 1 only: every output, whole.
run 0 "$out" "$vorball" channels "$@" --frames 0:1
for f in old.csv s.csv c.pdb p.pml v.mrc p.png; do
    [ -s $f ] || fail "channels wrote no $f"
done
expect_line old.csv "^frame,model,channel,"
no_temps

# A link as output: its target gets the result, the link stays.
echo old > target.tsv
ln -s target.tsv via.tsv
run 0 "$out" "$vorball" vertices --device ref in.xyzr -o via.tsv
[ -L via.tsv ] || fail "the output link was replaced by a file"
run 0 "$out" "$vorball" vertices --device ref in.xyzr -o plain.tsv
cmp -s target.tsv plain.tsv || fail "the link's target does not hold the vertices"
# Not a regular file: written in place.
run 0 "$out" "$vorball" vertices --device ref in.xyzr -o /dev/null
[ -c /dev/null ] || fail "/dev/null is no longer a device"
no_temps

# SIGTERM while channels writes: its temporary files go with it.
"$vorball" channels --device ref --grid 32 --repeat 400 "$corpus/data/ngl_md_ascii_trj.pdb" \
    -o term.csv --stats-file term_s.csv 2> /dev/null &
pid=$!
i=0
while [ $i -lt 100 ] && ! ls -A | grep -q 'term.*vorball-'; do
    sleep 0.05
    i=$((i + 1))
done
if kill -0 $pid 2> /dev/null; then
    kill -TERM $pid
    wait $pid
    [ ! -e term.csv ] && [ ! -e term_s.csv ] || fail "a stopped run left its outputs"
    no_temps
else
    wait $pid
    echo "note: channels ended before SIGTERM could stop it"
fi
echo "ok: outputs"
