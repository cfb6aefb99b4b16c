#!/bin/sh
# Periodic cost against the open run on the same atoms (issue 34): water
# boxes of 3,000 to 17,496 atoms (water_box.py), a protein alone in its MD
# box (adk, GRO, triclinic) and the first frame of an MD trajectory in PDB
# with CRYST1 (183 atoms in a 56 A box). Wall seconds and CPU seconds
# (user + system, which a loaded shared machine disturbs less) of `vorball
# vertices` (each the best of REPS), open and --periodic, on --device ref
# and the default (PoCL on a machine without a GPU), 2 threads.
# usage: run.sh VORBALL OUT_DIR [REPS]    (writes OUT_DIR/twocore.tsv)
vorball=$1 out=$2 reps=${3:-2}
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../../corpus/data
mkdir -p "$out/work" || exit 1
work=$out/work
for c in 10 14 18; do
    python3 "$here/water_box.py" $c > "$work/water$c.gro" || exit 1
done
gzip -dc "$data/adk_oplsaa_protein.gro.gz" > "$work/adk.gro"
awk '/^ENDMDL/ {exit} {print}' "$data/ngl_md_ascii_trj.pdb" > "$work/ngl_frame1.pdb"

# best WALL CPU: the least wall and the least CPU seconds of REPS runs
best() {
    bw= bc=
    i=0
    while [ $i -lt "$reps" ]; do
        t0=$(date +%s.%N)
        /usr/bin/time -f '%U %S' -o "$work/time.txt" "$@" > /dev/null 2>&1 ||
            { echo "failed: $*" >&2; exit 1; }
        t1=$(date +%s.%N)
        w=$(echo "$t1 - $t0" | bc)
        c=$(awk '{print $1 + $2}' "$work/time.txt")
        if [ -z "$bw" ] || [ "$(echo "$w < $bw" | bc)" = 1 ]; then bw=$w; fi
        if [ -z "$bc" ] || [ "$(echo "$c < $bc" | bc)" = 1 ]; then bc=$c; fi
        i=$((i + 1))
    done
    printf '%.2f %.2f' "$bw" "$bc"
}

printf 'input\tatoms\tdevice\topen_s\tperiodic_s\tratio\topen_cpu_s\tperiodic_cpu_s\tcpu_ratio\topen_vertices\tperiodic_vertices\tspheres_with_images\tfull_layer_spheres\trho\treach\n' \
    > "$out/twocore.tsv"
for input in water10.gro water14.gro water18.gro adk.gro ngl_frame1.pdb; do
    for device in ref auto; do
        f=$work/$input
        set -- $(best "$vorball" vertices --water --device $device --threads 2 "$f" \
                 -o "$work/open.tsv")
        to=$1 co=$2
        set -- $(best "$vorball" vertices --water --periodic --device $device --threads 2 "$f" \
                 -o "$work/periodic.tsv")
        tp=$1 cp=$2
        "$vorball" vertices --water --periodic --device $device --threads 2 --stats "$f" \
            -o /dev/null 2> "$work/stats.txt" > /dev/null
        stat() { awk -F'\t' -v k="$1" '$1 == k {print $2}' "$work/stats.txt"; }
        nopen=$(grep -vc '^#' "$work/open.tsv")
        nper=$(grep -vc '^#' "$work/periodic.tsv")
        printf '%s\t%s\t%s\t%s\t%s\t%.2f\t%s\t%s\t%.2f\t%s\t%s\t%s\t%s\t%.3f\t%.3f\n' "$input" \
            "$(stat periodic_atoms)" $device "$to" "$tp" "$(echo "$tp / $to" | bc -l)" "$co" "$cp" \
            "$(echo "$cp / $co" | bc -l)" "$nopen" "$nper" \
            "$(stat periodic_spheres)" "$(stat periodic_layer_spheres)" "$(stat periodic_rho)" \
            "$(stat periodic_reach)" \
            >> "$out/twocore.tsv"
        tail -1 "$out/twocore.tsv"
    done
done
