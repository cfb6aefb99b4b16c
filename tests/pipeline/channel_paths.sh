#!/bin/sh
# Issue 33: the channel graph's sweeps as batches (VORBALL_DEVICE_PATHS=1 or 2,
# core/discrete/vbc_paths.h) give the bytes of the per-component Dijkstra:
# table, centrelines, profile and the JSON less its clocks, on the twin
# (--device ref) at one and two threads, sequential and in flight, and on
# the kernels (PoCL forced by 2, with the device's components and clearances: a GPU's
# host analysis; then with the pore verdict's rasters too, VORBALL_DEVICE_WALLS=2),
# over the 10-frame MD trajectory, 1chb at grid 128 and
# crambin, both with their cavities (the cavities' two plain waves).
# usage: channel_paths.sh VORBALL CORPUS WORKDIR
vorball=$1 corpus=$2 work=$3
. "$(dirname "$0")/lib.sh"
fresh_dir "$work/channel_paths"
top="$corpus/data/ngl_md_ascii_trj.pdb" xtc="$corpus/data/ngl_md_10frames.xtc"

# case NAME PATHS THREADS AHEAD ARGS...: one run, NAME.csv, .pdb, .prof and
# the JSON without "ms", "clock" and "device" in NAME.sj.
case_run() {
    name=$1 paths=$2 threads=$3 ahead=$4
    shift 4
    VORBALL_DEVICE_PATHS=$paths VORBALL_THREADS=$threads VORBALL_FRAMES_AHEAD=$ahead \
        run 0 "$name.log" "$vorball" channels "$@" --centerlines "$name.pdb" --profile "$name.prof" \
        --json -o "$name.json"
    grep -v '"ms"\|"clock"\|"device"' "$name.json" > "$name.sj"
    VORBALL_DEVICE_PATHS=$paths VORBALL_THREADS=$threads VORBALL_FRAMES_AHEAD=$ahead \
        run 0 "$name.clog" "$vorball" channels "$@" -o "$name.csv"
}
same() {
    for ext in csv pdb prof sj; do
        cmp -s "$1.$ext" "$2.$ext" || { diff "$1.$ext" "$2.$ext" | head -10 >&2; fail "$2.$ext differs from $1.$ext"; }
    done
}
# The batches ran: the JSON's graph clock is not 0 in every frame.
timed() {
    grep -o '"graph": [0-9.]*' "$1.json" | grep -qv '"graph": 0.000' || fail "$1: no batch sweep timed"
}

traj="$top --traj $xtc --grid 64"
chb="--grid 128 --cavities $corpus/data/1chb_hole2.pdb"
crn="--cavities $corpus/data/1crn.pdb"
for input in traj chb crn; do
    eval "args=\$$input"
    # shellcheck disable=SC2086
    case_run "${input}_dij" 0 2 2 --device ref $args
    for ta in "1 0" "2 2"; do
        set -- $ta
        # shellcheck disable=SC2086
        case_run "${input}_twin$1$2" 1 "$1" "$2" --device ref $args
        same "${input}_dij" "${input}_twin$1$2"
        timed "${input}_twin$1$2"
    done
    # shellcheck disable=SC2086
    VORBALL_DEVICE_GRAPH=1 VORBALL_DEVICE_CLEARANCE=1 case_run "${input}_pocl" 2 2 2 --device cpu $args
    same "${input}_dij" "${input}_pocl"
    timed "${input}_pocl"
    # The pore verdict's rasters on the kernel (vbc_walls.h, forced on PoCL
    # by 2) as well: a GPU run's whole host side, at one and two threads.
    for t in 1 2; do
        # shellcheck disable=SC2086
        VORBALL_DEVICE_WALLS=2 VORBALL_DEVICE_GRAPH=1 VORBALL_DEVICE_CLEARANCE=1 \
            case_run "${input}_walls$t" 2 "$t" 2 --device cpu $args
        same "${input}_dij" "${input}_walls$t"
    done
done
# A path that is no pore shows its buried length in W808 only: adenylate
# kinase's (walled 0 A) judged from the kernel's rasters as from the cell list.
for d in ref cpu; do
    VORBALL_DEVICE_WALLS=2 VORBALL_THREADS=2 run 0 "adk_$d.log" "$vorball" channels --device "$d" \
        "$corpus/data/adk_open.pdb.gz" -o "adk_$d.csv"
    grep W808 "adk_$d.log" > "adk_$d.w808" || fail "adk_open ($d): no W808"
done
cmp -s adk_ref.w808 adk_cpu.w808 || fail "adk_open: W808 differs on the rasters: $(cat adk_cpu.w808)"
[ "$(grep -c '"frame"' traj_dij.sj)" -eq 10 ] || fail "traj: $(grep -c '"frame"' traj_dij.sj) frames, expected 10"
grep -q '"kind": "cavity"' chb_dij.sj || fail "1chb: no cavity traced"
echo "channel_paths: ok"
