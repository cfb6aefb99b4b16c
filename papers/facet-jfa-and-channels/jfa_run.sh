#!/bin/sh
# Reruns the JFA / Facet-JFA measurements of facet-jfa-and-channels.txt
# (Sec. 3: the 2D speed-up figure, the 3D 512^3 x 1000 point) plus the error
# figures of every variant, with `vorball jfa --check --json`.
#
#   papers/facet-jfa-and-channels/jfa_run.sh VORBALL OUTDIR [quick]
#
# VORBALL is the binary, OUTDIR receives one JSON file per configuration;
# jfa_tables.py and jfa_speedup.gp turn them into the tables and the plot.
# "quick" keeps only grids up to 1024^2 and 128^3 (a CPU/PoCL smoke run).
# Devices: --device auto (the GPU when there is one). Each time is the mean
# over --repeat runs of the algorithm on the device (uploads, downloads and
# host preprocessing excluded, as in the paper).
# JFA_CHECK= (set and empty) leaves out the comparison with the exact diagram:
# times only, for a kernel change that keeps the labels bit for bit (the
# error figures then come from an earlier run: jfa_tables.py's second argument).
set -u
V=$1
O=$2
QUICK=${3:-}
CHECK=${JFA_CHECK---check}
HERE=$(cd "$(dirname "$0")" && pwd)
CORPUS=$HERE/../../corpus/data
mkdir -p "$O"

run() { # name, then vorball jfa arguments
    name=$1
    shift
    echo "== $name: $*" >&2
    start=$(date +%s)
    timeout 300 "$V" jfa --device auto --json $CHECK "$@" -o "$O/$name.json" 2> "$O/$name.err"
    echo "   rc $? in $(($(date +%s) - start)) s" >&2
}

if [ -n "$QUICK" ]; then
    sizes="256 512 1024"
    n3=128
    big3=128
else
    sizes="256 512 1024 2048 4096"
    n3=256
    big3=512
fi

# The performance target: JFA+1 on 256^3 with 13,573 seeds (2OAU's atom count).
run target3d -d 3 -n $n3 -k 13573 -V jfa+1,jfa,facet --repeat 50

# Fig. 4: 2D, grids 256^2 .. 4096^2, 10 .. 100,000 uniform seeds.
for n in $sizes; do
    for k in 10 100 1000 10000 100000; do
        run "fig2d_n${n}_k${k}" -d 2 -n "$n" -k "$k" -V jfa,jfa+1,facet,exact --repeat 10
    done
done

# The 3D point: 512^3, 1,000 seeds (the paper: about 6x over JFA).
run fig3d_n${big3}_k1000 -d 3 -n $big3 -k 1000 -V jfa+1,facet,exact --repeat 10

# Errors of every variant by seed distribution, and on real atom centres.
for d in uniform clustered shell; do
    run "dist3d_${d}" -d 3 -n $n3 -k 1000 --dist "$d" -V all --repeat 10
    run "dist2d_${d}" -d 2 -n 1024 -k 1000 --dist "$d" -V all --repeat 10
done
run protein_3pqr --protein "$CORPUS/3pqr.pqr" -n $n3 -V all --repeat 10
run protein_4yvs --protein "$CORPUS/4yvs_ev71_capsid.cif" -n $n3 -V all --repeat 10

# Pictures: a 2D Facet-JFA diagram and three slices through a protein's.
"$V" jfa --device auto -d 2 -n 1024 -k 100 -V facet --png "$O/facet2d_1024_k100.png" \
    -o /dev/null 2>> "$O/pictures.err"
"$V" jfa --device auto --protein "$CORPUS/3pqr.pqr" -n $n3 -V facet \
    --slice $((n3 / 4)),$((n3 / 2)),$((3 * n3 / 4)) --png "$O/protein_3pqr_slices.png" \
    -o /dev/null 2>> "$O/pictures.err"
exit 0
