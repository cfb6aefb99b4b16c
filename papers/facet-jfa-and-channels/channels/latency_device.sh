#!/bin/bash
# Issue 33 on a GPU: per-stage median ms per frame of `vorball channels
# --device gpu` at grids 128 and 256 for adk_oplsaa (47,681 atoms, XTC, 10
# frames, reading included), 1chb (4,298 atoms, --repeat 5) and YiiP_lipids
# (43,480 atoms, --repeat 5), each JSON less its clocks compared with
# --device ref's (IDENTICAL or DIFFERS), and the process's wall and CPU.
#
# usage: latency_device.sh VORBALL MDA [THREADS...]
#   VORBALL  the binary;  MDA  folders (colon-separated, searched in order)
#            holding adk_oplsaa.gro, adk_oplsaa.xtc and YiiP_lipids.gro.gz;
#            THREADS  VORBALL_THREADS values to run ("-": unset, the machine's
#            threads; the default)
#   DATA     the corpus data (default this repository's corpus/data)
#   DEV      the device measured (default gpu), against --device ref
# e.g. on the device host, from the repository root:
#   bash papers/facet-jfa-and-channels/channels/latency_device.sh build-carry/vorball-g \
#       build-carry:build-carry/in40 - 1 16
# Needs bash, python3 (standard library).
set -u
if [ $# -lt 2 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
V=$1 MDA=$2; shift 2
find_mda() { local d; IFS=: read -ra ds <<< "$MDA"; for d in "${ds[@]}"; do
    [ -e "$d/$1" ] && { echo "$d/$1"; return; }; done; echo "MISSING/$1"; }
here=$(cd "$(dirname "$0")" && pwd)
D=${DATA:-$(cd "$here/../../../corpus/data" && pwd)}
T=$(mktemp -d) || exit 3
strip() { grep -v -E '"(tool|device|options)":|"ms": \{|"clock": \{' "$1"; }
one() { # label grid threads, then the input and options
    local lab=$1 g=$2 th=$3; shift 3
    local e=(); [ "$th" != - ] && e=(VORBALL_THREADS=$th)
    env "${e[@]}" "$V" --quiet channels --device ref --grid "$g" --json -o "$T/r.json" "$@" 2> /dev/null ||
        { echo "$lab grid $g ref FAILED"; return; }
    local s=$(date +%s.%N)
    env "${e[@]}" "$V" --quiet channels --device "${DEV:-gpu}" --grid "$g" --json -o "$T/g.json" "$@" 2> /dev/null ||
        { echo "$lab grid $g ${DEV:-gpu} FAILED"; return; }
    local w=$(python3 -c "import time; print('%.3f' % (time.time() - $s))")
    cmp -s <(strip "$T/r.json") <(strip "$T/g.json") && local id=IDENTICAL || local id=DIFFERS
    python3 - "$T/g.json" "$lab" "$g" "$th" "$w" "$id" <<'PY'
import json, statistics as S, sys
d = json.load(open(sys.argv[1])); fr = d["frames"]
med = {k: round(S.median(f["ms"][k] for f in fr), 2) for k in fr[0]["ms"]}
cl = {k: round(S.median(f["clock"][k] for f in fr), 2) for k in ("frame", "cpu") if k in fr[0]["clock"]}
print("%s grid %s threads %s frames %d wall_s %s %s" % (sys.argv[2], sys.argv[3], sys.argv[4], len(fr),
      sys.argv[5], sys.argv[6]), med, "clock", cl)
PY
}
nvidia-smi -L 2> /dev/null; nproc; "$V" --version | head -1
for th in "${@:--}"; do
    for g in 128 256; do
        one adk_oplsaa_xtc "$g" "$th" "$(find_mda adk_oplsaa.gro)" --traj "$(find_mda adk_oplsaa.xtc)"
        one 1chb "$g" "$th" "$D/1chb_hole2.pdb" --repeat 5
        one YiiP "$g" "$th" "$(find_mda YiiP_lipids.gro.gz)" --repeat 5
    done
done
rm -rf "$T"
