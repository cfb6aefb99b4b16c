#!/bin/sh
# Table 1 and Fig. 13 runs of `vorball bench` on one device, as JSON lines.
# usage: run_bench.sh VORBALL DEVICE INPUT_DIR OUT_DIR [table1|fig13]
# 1chb keeps its 284 waters (--water) to be the 4582-atom stand-in for 1JD0.
vorball=$1 device=$2 in=$3 out=$4 what=${5:-table1}
mkdir -p "$out" || exit 1
case $what in
table1)
    for f in 1crn.pdb 1crn_apbs.xyzr 1chb_hole2.pdb 3pqr.xyzr; do
        extra=""
        [ "$f" = 1chb_hole2.pdb ] && extra=--water
        "$vorball" bench --device "$device" --samples 30,60,80,100 $extra --json \
            "$in/$f" > "$out/table1_${device}_${f%.*}.json" || exit 1
    done ;;
fig13)
    for f in 1crn_apbs.xyzr 3pqr.xyzr 1crn.pdb 1grm_single_hole2.pdb; do
        "$vorball" bench --device "$device" --samples 4,6,8,10,15,20,30,40,60,80 --json \
            "$in/$f" > "$out/fig13_${device}_${f%.*}.json" || exit 1
    done ;;
esac
