#!/bin/bash
# HOLE 2 (osmart/hole2) against `vorball channels` on its own examples: gramicidin A
# (1grm_single_hole2.pdb), the cholera toxin B pentamer (1chb_hole2.pdb) and, when
# MALTOPORIN is set, the maltoporin trimer (1af6, 10,050 protein atoms, one pore per
# monomer), with the same van der Waals radii (HOLE's rad/simple.rad, one value per element).
#
# usage: hole_compare.sh HOLEBIN VORBALL OUTDIR
#   HOLEBIN  the hole binary (built apart); its radius file is HOLE_RAD, by default
#            HOLE's install layout: $(dirname HOLEBIN)/../share/hole2/rad/simple.rad
#   OUTDIR   gets per structure NAME (1grm, 1chb, 1af6): NAME_hole.inp / .out / .sph (HOLE's
#            input, output and sphere centres), NAME_vorball.json (`vorball channels
#            --json`), NAME_summary.json (minimum radius and its axial position for
#            both, HOLE's conductance estimate, the matched vorball channel),
#            NAME_hole_profile.tsv, NAME_vorball_profile.tsv, NAME_profiles.tsv (side
#            by side on HOLE's axial positions), and hole_compare.tsv (one row each)
# HOLE's input is the example's own (examples/01_gramicidin_1grm/hole.inp,
# examples/02_choleratoxin_1chb/02_hole.inp) with the radius file's path, a fixed
# random seed ('raseed', HOLE_SEED, default 1: HOLE otherwise seeds from the clock)
# and, for 1chb, without 'shorto 2' so that the profile is printed (output only); for
# 1af6 examples/03_maltoporin_1af6/03_example.inp (HOLE's cvect and cpoint: the pore of
# chain B through one of its sugars; vorball gets them as --axis and --through, and
# --ignore for HOLE's ignore card).
# Environment (optional):
#   DATA=DIR        the PDB files (default: the repository's corpus/data)
#   HOLE_SEED=S     HOLE's random seed;  HOLE_SEEDS="S ..." extra seeds for the spread
#                   of HOLE's own minimum radius (default "2 3 4 5")
#   GRID_1grm, GRID_1chb   vorball grid (default 128, vorball's own);  PROBE_1grm,
#                   PROBE_1chb (default 1.4, vorball's own: its pore passes
#                   constrictions below the probe)
#   DEVICE=D        vorball device (default auto)
#   MALTOPORIN=FILE 03_1af6.pdb of HOLE's examples (examples/03_maltoporin_1af6/; not
#                   in this repository: PDB 1AF6 as HOLE ships it); unset: skipped
#   GRID_1af6, PROBE_1af6   as for the others (default 128, 1.4)
# Needs bash, python3 (standard library) and the binaries; nothing is built here.
set -u
if [ $# -lt 3 ]; then
    sed -n '2,/^# Needs/p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
HOLE=$1 VORBALL=$2 OUT=$3
here=$(cd "$(dirname "$0")" && pwd)
DATA=${DATA:-$here/../../corpus/data}
HOLE_RAD=${HOLE_RAD:-$(dirname "$HOLE")/../share/hole2/rad/simple.rad}
HOLE_SEED=${HOLE_SEED:-1}
HOLE_SEEDS=${HOLE_SEEDS-"2 3 4 5"}
DEVICE=${DEVICE:-auto}
[ -r "$HOLE_RAD" ] || { echo "hole_compare: no radius file $HOLE_RAD (set HOLE_RAD)" >&2; exit 3; }
mkdir -p "$OUT" || exit 3
OUT=$(cd "$OUT" && pwd)
py="python3 $here/hole_compare.py"
cp "$HOLE_RAD" "$OUT/hole.rad"
$py radii "$OUT/hole.rad" "$OUT/vorball.radii" || exit 6

hole_input() { # name pdb seed -> HOLE input on stdout (paths relative to OUTDIR)
    case $1 in
    1grm) printf '%s\n' "coord $2" "radius hole.rad" "sphpdb $1_hole$3.sph" "endrad 5." "raseed $3" ;;
    1chb) printf '%s\n' "coord $2" "radius hole.rad" "ignore hoh tip wat" "conn" \
              "sphpdb $1_hole$3.sph" "raseed $3" ;;
    1af6) printf '%s\n' "coord $2" "radius hole.rad" "ignore FRU GLC MG HOH" "cvect 0.0 0.0 1.0" \
              "cpoint -14.285 47.809 82.707" "sphpdb $1_hole$3.sph" "raseed $3" ;;
    esac
}

tsv=$OUT/hole_compare.tsv
printf 'name\thole_rmin_A\thole_s_A\thole_gmacro_pS\thole_rmin_range_A\tvorball_bottleneck_A\tvorball_s_A\tdelta_rmin_A\tdelta_s_A\tvorball_r_at_hole_min\thole_r_at_vorball_min\tvorball_channel\tcoverage\tgrid\tprobe\tvoxel_A\tvorball_gmacro_pS\n' > "$tsv"
names="1grm 1chb"
[ -n "${MALTOPORIN:-}" ] && names="$names 1af6"
for name in $names; do
    case $name in
    1grm) pdb=1grm_single_hole2.pdb grid=${GRID_1grm:-128} probe=${PROBE_1grm:-1.4} vopt=(--end-radius 5) ;;
    1chb) pdb=1chb_hole2.pdb grid=${GRID_1chb:-128} probe=${PROBE_1chb:-1.4} vopt=() ;;
    1af6) pdb=03_1af6.pdb grid=${GRID_1af6:-128} probe=${PROBE_1af6:-1.4}
          vopt=(--ignore FRU,GLC,MG,HOH --axis 0,0,1 --through -14.285,47.809,82.707) ;;
    esac
    if [ "$name" = 1af6 ]; then cp "$MALTOPORIN" "$OUT/$pdb" || exit 3; else cp "$DATA/$pdb" "$OUT/$pdb" || exit 3; fi
    extra=()
    for s in $HOLE_SEED $HOLE_SEEDS; do
        hole_input "$name" "$pdb" "$s" > "$OUT/${name}_hole$s.inp"
        echo "hole_compare: $name: HOLE (raseed $s)" >&2
        (cd "$OUT" && "$HOLE" < "${name}_hole$s.inp" > "${name}_hole$s.out" 2> "${name}_hole$s.err")
        echo "hole_compare:   rc $?" >&2
        [ "$s" != "$HOLE_SEED" ] && extra+=("$OUT/${name}_hole$s.out")
    done
    rm -f "$OUT/sr_gseed_tempfile"
    echo "hole_compare: $name: vorball channels (grid $grid, probe $probe)" >&2
    "$VORBALL" channels --device "$DEVICE" --radii "$OUT/vorball.radii" --grid "$grid" --probe "$probe" \
        "${vopt[@]}" --json -o "$OUT/${name}_vorball.json" --centerlines "$OUT/${name}_vorball_centerlines.pdb" \
        "$OUT/$pdb" 2> "$OUT/${name}_vorball.err"
    echo "hole_compare:   rc $?" >&2
    $py compare "$name" "$OUT/${name}_hole$HOLE_SEED.out" "$OUT/${name}_hole$HOLE_SEED.sph" \
        "$OUT/${name}_vorball.json" "$OUT" "${extra[@]}" || exit 6
    python3 - "$OUT/${name}_summary.json" "$tsv" "$grid" "$probe" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
h, v = s["hole"], s["vorball"]
hm, vb = s.get("hole_min_at") or {}, v.get("bottleneck") or {}
def f(x, fmt="%.3f"):
    return "" if x is None else (fmt % x if isinstance(x, float) else str(x))
rng = s.get("hole_rmin_range_A")
row = [s["name"], f(h.get("rmin_A"), "%.5f"), f(hm.get("s")), f(h.get("gmacro_pS"), "%.1f"),
       "%.5f-%.5f" % tuple(rng) if rng else "", f(vb.get("radius")), f(vb.get("s")), f(s.get("delta_rmin_A")),
       f(s.get("delta_s_A")), f(s.get("vorball_radius_at_hole_min")), f(s.get("hole_radius_at_vorball_min")),
       f(v.get("matched_channel")), f(v.get("matched_coverage")), sys.argv[3], sys.argv[4],
       f(v.get("voxel_A")), f((v.get("pore") or {}).get("g_macro_pS"), "%.1f")]
open(sys.argv[2], "a").write("\t".join(row) + "\n")
EOF
done
column -t -s "$(printf '\t')" "$tsv" >&2 2>/dev/null || cat "$tsv" >&2
