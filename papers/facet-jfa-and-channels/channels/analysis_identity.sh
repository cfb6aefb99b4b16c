#!/bin/bash
# The 55-file identity of paths_2core.md: 11 runs of `vorball channels`, each
# writing 5 files (the channel CSV, the profile CSV, the centrelines PDB, the
# PyMOL script, and the JSON less its tool, device, options, ms and clock
# lines; a few runs add a per-frame PDB beside the PyMOL script). Run it for
# two binaries and compare the folders with cmp.
#
# usage: analysis_identity.sh VORBALL OUTDIR
#   DATA  the corpus data (default: this repository's corpus/data)
#   MDA   the MDAnalysis test files YiiP_lipids.gro.gz, adk_oplsaa.gro and
#         adk_oplsaa.xtc (GPL-2+, not in the repository; default /work/peers/mda)
#   DEV   --device (default ref); with cpu and VORBALL_DEVICE_CLEARANCE=1
#         VORBALL_DEVICE_GRAPH=1 a GPU run's host analysis on PoCL
# e.g. for b in old new; do analysis_identity.sh $b/vorball out.$b; done
#      for f in out.old/*; do cmp "$f" "out.new/${f##*/}"; done
set -u
if [ $# -lt 2 ]; then
    sed -n '2,/^# e.g./p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
V=$1 O=$2
here=$(cd "$(dirname "$0")" && pwd)
D=${DATA:-$(cd "$here/../../../corpus/data" && pwd)} M=${MDA:-/work/peers/mda}
mkdir -p "$O" || exit 3
run() { # name, then the input and options in ARGS
    n=$1
    "$V" channels "${ARGS[@]}" --device "${DEV:-ref}" -o "$O/$n.csv" --profile "$O/$n.prof.csv" \
        --centerlines "$O/$n.pdb" --pymol "$O/$n.pml" 2> "$O/$n.err" || echo "FAIL $n" >&2
    "$V" channels "${ARGS[@]}" --device "${DEV:-ref}" --json -o "$O/$n.json.full" 2>> "$O/$n.err" ||
        echo "FAIL $n json" >&2
    grep -v -E '"(tool|device|options)":|"ms": \{|"clock": \{' "$O/$n.json.full" > "$O/$n.json"
    rm -f "$O/$n.json.full"
    sed -i "s|$O/||g" "$O/$n.pml"
}
ARGS=("$D/1grm_single_hole2.pdb"); run 1grm
ARGS=("$D/1chb_hole2.pdb"); run 1chb
ARGS=("$D/1af6_hole2.pdb.gz"); run 1af6
ARGS=("$D/1af6_hole2.pdb.gz" --keep-ligands); run 1af6_lig
ARGS=("$M/YiiP_lipids.gro.gz"); run yiip
ARGS=("$D/adk_open.pdb.gz"); run adk_open
ARGS=("$D/adk_open.pdb.gz" --cavities); run adk_open_cav
ARGS=("$D/1crn.pdb"); run 1crn
ARGS=("$D/1crn.pdb" --cavities); run 1crn_cav
ARGS=("$M/adk_oplsaa.gro" --traj "$M/adk_oplsaa.xtc" --frames 0:3); run adk_xtc
ARGS=("$D/ngl_md_ascii_trj.pdb"); run ngl_md
ls "$O" | grep -vc '\.err$'
