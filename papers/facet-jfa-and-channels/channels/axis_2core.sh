#!/bin/bash
# Channels at the defaults beside HOLE 2 with the same radius file (issue 32):
# vorball finds the axis itself (no --axis); HOLE gets its examples' input
# (for maltoporin its cvect and cpoint: HOLE's own guess fails on the trimer).
# Both read HOLE's .rad file as it is (vorball matches its rows per atom and
# residue name as HOLE does). CPU time (user + sys, /usr/bin/time) of each run.
#
# usage: axis_2core.sh HOLE_DIR VORBALL OUTDIR [YIIP_GRO]
#   HOLE_DIR  a HOLE 2 checkout built apart (exe/hole, rad/*.rad; never committed)
#   YIIP_GRO  optional: MDAnalysis' YiiP_lipids.gro.gz (GPL-2+, kept out of the
#             repository): YiiP in a POPE/POPG bilayer, vorball at the defaults
#             (the lipids left out, W809; the axis their normal) beside HOLE on
#             the same atoms along vorball's axis (cvect, cpoint), and HOLE's own guess
# Writes OUTDIR/axis_2core.tsv: name, radii, HOLE's minimum radius per seed (1 2 3),
# HOLE's CPU seconds (seed 1), vorball's bottleneck, axis source and CPU seconds.
set -u
[ $# -eq 3 ] || [ $# -eq 4 ] || { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
HD=$1 V=$2 OUT=$3 YIIP=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../../corpus/data
mkdir -p "$OUT" && cd "$OUT" || exit 3
cp "$data/1grm_single_hole2.pdb" 1grm.pdb
cp "$data/1chb_hole2.pdb" 1chb.pdb
gzip -dc "$data/1af6_hole2.pdb.gz" > 1af6.pdb
awk 'substr($0,1,4)=="ATOM" && substr($0,22,1)=="B"; END { print "END" }' 1af6.pdb > 1af6_B.pdb

cpu() { # file written by /usr/bin/time -f '%U %S' -> user + sys
    tail -1 "$1" | awk '{ printf "%.2f", $1 + $2 }'
}
hole_run() { # name pdb rad seed extra-cards...
    local name=$1 pdb=$2 rad=$3 seed=$4
    shift 4
    { printf '%s\n' "coord $pdb" "radius $HD/rad/$rad.rad" "sphpdb ${name}_$rad$seed.sph" "raseed $seed"
      printf '%s\n' "$@"; } > "${name}_$rad$seed.inp"
    /usr/bin/time -f '%U %S' -o "${name}_$rad$seed.time" "$HD/exe/hole" < "${name}_$rad$seed.inp" \
        > "${name}_$rad$seed.out" 2> /dev/null
    rm -f sr_gseed_tempfile
    awk '/Minimum radius found/ { print $4 }' "${name}_$rad$seed.out"
}
vorball_run() { # name pdb rad options... -> "bottleneck source"
    local name=$1 pdb=$2 rad=$3
    shift 3
    # The defaults: without a GPU, --device auto is the plain-C twin (no OpenCL).
    /usr/bin/time -f '%U %S' -o "${name}_$rad.vtime" "$V" channels \
        --radii "$HD/rad/$rad.rad" "$@" --json -o "${name}_$rad.json" "$pdb" 2> "${name}_$rad.err"
    python3 -c "import json,sys; f=json.load(open(sys.argv[1]))['frames'][0]; p=f.get('pore')
print('%.3f %s' % (f['channels'][0]['bottleneck_A'], p['axis_from']) if p else 'none none')" "${name}_$rad.json"
}
printf 'name\tradii\thole_seed1\thole_seed2\thole_seed3\thole_cpu_s\tvorball\taxis\tvorball_cpu_s\n' > axis_2core.tsv
row() { # name pdb rad "vorball options" hole-cards...
    local name=$1 pdb=$2 rad=$3 vopt=$4
    shift 4
    local h1 h2 h3 v
    h1=$(hole_run "$name" "$pdb" "$rad" 1 "$@")
    h2=$(hole_run "$name" "$pdb" "$rad" 2 "$@")
    h3=$(hole_run "$name" "$pdb" "$rad" 3 "$@")
    # shellcheck disable=SC2086
    v=$(vorball_run "$name" "$pdb" "$rad" $vopt)
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$rad" "$h1" "$h2" "$h3" \
        "$(cpu "${name}_${rad}1.time")" ${v% *} ${v#* } "$(cpu "${name}_$rad.vtime")" >> axis_2core.tsv
}
for rad in simple bondi amberuni; do
    row 1grm 1grm.pdb $rad "" "endrad 5."
done
row 1chb 1chb.pdb simple "" "ignore hoh tip wat"
# vorball at plain defaults: the sugars and ions are left out as ligands (W811).
row 1af6 1af6.pdb simple "" "ignore FRU GLC MG HOH" "cvect 0.0 0.0 1.0" \
    "cpoint -14.285 47.809 82.707"
row 1af6_B 1af6_B.pdb simple "" "cvect 0.0 0.0 1.0" "cpoint -14.285 47.809 82.707"
if [ -n "$YIIP" ]; then
    # GRO (nm) to PDB (A) for HOLE; HOLE's simple.rad has no zinc (its
    # dummy-atom zinc model ZNM), so both leave ZNM out; HOLE guesses its axis.
    gzip -dcf "$YIIP" | awk 'NR == 2 { last = $1 + 2 } NR > 2 && NR <= last {
        n++; rn = substr($0, 6, 5); an = substr($0, 11, 5); gsub(/ /, "", rn); gsub(/ /, "", an)
        printf "ATOM  %5d %-4s %-4s %4d    %8.3f%8.3f%8.3f  1.00  0.00\n", n % 100000,
            length(an) < 4 ? " " an : an, rn, substr($0, 1, 5) % 10000,
            substr($0, 21, 8) * 10, substr($0, 29, 8) * 10, substr($0, 37, 8) * 10 }
        END { print "END" }' > yiip.pdb
    # vorball first: its axis (the membrane's normal since axis32c) and
    # start are HOLE's cvect and cpoint, the same axis for both.
    cp "$YIIP" yiip.gro.gz
    v=$(vorball_run yiip yiip.gro.gz simple --ignore ZNM)
    cv=$(python3 -c "import json,sys; p=json.load(open(sys.argv[1]))['frames'][0]['pore']
print('cvect %s %s %s' % tuple(p['axis'])); print('cpoint %s %s %s' % tuple(p['start']))" yiip_simple.json)
    h1=$(hole_run yiip yiip.pdb simple 1 "ignore POPE POPG SOL ZNM" "$cv")
    h2=$(hole_run yiip yiip.pdb simple 2 "ignore POPE POPG SOL ZNM" "$cv")
    h3=$(hole_run yiip yiip.pdb simple 3 "ignore POPE POPG SOL ZNM" "$cv")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' yiip simple "$h1" "$h2" "$h3" \
        "$(cpu yiip_simple1.time)" ${v% *} ${v#* } "$(cpu yiip_simple.vtime)" >> axis_2core.tsv
    # HOLE's own axis guess (x here), as before.
    h1=$(hole_run yiipguess yiip.pdb simple 1 "ignore POPE POPG SOL ZNM")
    h2=$(hole_run yiipguess yiip.pdb simple 2 "ignore POPE POPG SOL ZNM")
    h3=$(hole_run yiipguess yiip.pdb simple 3 "ignore POPE POPG SOL ZNM")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t\t\t\n' yiip_hole_guess simple "$h1" "$h2" "$h3" \
        "$(cpu yiipguess_simple1.time)" >> axis_2core.tsv
fi
cat axis_2core.tsv
