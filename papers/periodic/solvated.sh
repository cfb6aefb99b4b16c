#!/bin/sh
# A real solvated MD system, periodic (issue 34): the atoms of a GRO file
# (TIP4P's virtual site MW left out) as balls (gro_xyzr.py), `vorball
# vertices` open and periodic in the GRO's box on the same balls (ref, 2
# threads), `vorball verify --periodic` of the periodic file, Voronota 1.29
# `calculate-vertices` (open, 1 thread: it has no periodic mode) on the same
# balls, then the periodic diagram of the XTC's frames, each in the box it
# carries (the GRO as topology, --select 'not name MW'). CPU seconds =
# user + system of /usr/bin/time. The MD files stay outside the repository
# (MDAnalysis' test data, GPL-2+): give their paths.
# usage: solvated.sh VORBALL GRO XTC OUT_DIR [VORONOTA] [FRAMES A:B:S]
vorball=$1 gro=$2 xtc=$3 out=$4 voronota=${5:-} frames=${6:-0:10}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out" || exit 1
python3 "$here/gro_xyzr.py" "$gro" > "$out/balls.xyzr" 2> "$out/box.txt" || exit 1
box=$(cat "$out/box.txt")
cpu() { awk '{printf "%.2f", $1 + $2}' "$1"; }
wall() { awk '{print $3}' "$1"; }
count() { grep -vc '^#' "$1"; }
run() { # NAME command...: time it into OUT/NAME.time
    name=$1
    shift
    /usr/bin/time -f '%U %S %e %M' -o "$out/$name.time" "$@" || { echo "failed: $*" >&2; exit 1; }
}
run open "$vorball" vertices --device ref --threads 2 "$out/balls.xyzr" -o "$out/open.tsv"
run periodic "$vorball" vertices --device ref --threads 2 --stats "$out/balls.xyzr" --box $box \
    -o "$out/periodic.tsv" 2> "$out/periodic.stats"
run verify "$vorball" verify --periodic "$out/balls.xyzr" "$out/periodic.tsv" --box $box \
    > "$out/verify.txt" 2>&1
stat() { awk -F'\t' -v k="$1" '$1 == k {print $2}' "$out/periodic.stats"; }
{
    printf 'run\tatoms\tcpu_s\twall_s\tmax_rss_kb\tvertices\tspheres_with_images\n'
    n=$(wc -l < "$out/balls.xyzr")
    printf 'vorball open\t%s\t%s\t%s\t%s\t%s\t\n' "$n" "$(cpu "$out/open.time")" \
        "$(wall "$out/open.time")" "$(awk '{print $4}' "$out/open.time")" "$(count "$out/open.tsv")"
    printf 'vorball periodic\t%s\t%s\t%s\t%s\t%s\t%s\n' "$n" "$(cpu "$out/periodic.time")" \
        "$(wall "$out/periodic.time")" "$(awk '{print $4}' "$out/periodic.time")" \
        "$(count "$out/periodic.tsv")" "$(stat periodic_spheres)"
    printf 'vorball verify --periodic\t%s\t%s\t%s\t%s\t\t\n' "$n" "$(cpu "$out/verify.time")" \
        "$(wall "$out/verify.time")" "$(awk '{print $4}' "$out/verify.time")"
    if [ -n "$voronota" ]; then
        OMP_NUM_THREADS=1 run voronota "$voronota" calculate-vertices < "$out/balls.xyzr" \
            > "$out/voronota.txt"
        printf 'voronota 1.29 open\t%s\t%s\t%s\t%s\t%s\t\n' "$n" "$(cpu "$out/voronota.time")" \
            "$(wall "$out/voronota.time")" "$(awk '{print $4}' "$out/voronota.time")" \
            "$(wc -l < "$out/voronota.txt")"
    fi
} > "$out/solvated.tsv"
cat "$out/solvated.tsv"
if [ -n "$xtc" ] && [ "$frames" != - ]; then
    run frames "$vorball" vertices --device ref --threads 2 --stats --water --select 'not name MW' \
        --traj "$xtc" --frames "$frames" "$gro" -o "$out/frames.tsv" 2> "$out/frames.stats"
    grep '^frame' "$out/frames.stats" > "$out/frames_counts.tsv"
    printf 'frames %s: %s CPU s, %s wall s\n' "$frames" "$(cpu "$out/frames.time")" \
        "$(wall "$out/frames.time")" | tee -a "$out/solvated.tsv"
    cat "$out/frames_counts.tsv"
fi
