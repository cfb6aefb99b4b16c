#!/bin/sh
# Writes the benchmark inputs of Table 1 / Fig. 13 into DIR from DATA
# (corpus/data, copies of ../shared/data with provenance): PDB files are used as they are; PQR files from PDB2PQR
# with the PARSE force field give most hydrogens radius 0, which is not a
# sphere, so those hydrogens get Bondi's 1.2 A (the paper: "hydrogen atoms
# all have the same radii"); coordinates keep their decimals exactly.
# usage: prepare_inputs.sh DATA_DIR OUT_DIR
data=$1 out=$2
mkdir -p "$out" || exit 1
for f in 1crn_apbs 3pqr; do
    awk '($1 == "ATOM" || $1 == "HETATM") {
            r = $NF; if (r + 0 == 0) r = "1.2";
            print $(NF - 4), $(NF - 3), $(NF - 2), r }' "$data/$f.pqr" > "$out/$f.xyzr" || exit 1
done
for f in 1crn.pdb 1chb_hole2.pdb 1grm_single_hole2.pdb; do
    cat "$data/$f" > "$out/$f" || exit 1
done
