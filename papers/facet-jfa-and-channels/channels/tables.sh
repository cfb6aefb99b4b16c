#!/bin/sh
# Turns the FPS runs of bench.sh into a markdown table:
#   tables.sh OUTDIR > fps.md
# Columns: per-stage means over the repeats (ms), the GPU-stage FPS
# (upload + JFA + masks + compaction + clearances + list download) and the
# FPS of the whole frame with the host analysis (components, centrelines).
O=$1
echo "| input | grid | JFA | upload ms | JFA ms | masks ms | analysis ms | GPU stages FPS | full FPS | channel voxels |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for f in "$O"/fps_*_stats.csv; do
    base=$(basename "$f" _stats.csv)
    mol=$(echo "$base" | cut -d_ -f2)
    n=$(echo "$base" | cut -d_ -f3)
    v=$(echo "$base" | cut -d_ -f4)
    err="$O/$base.err"
    gpu=$(sed -n 's/.*GPU stages [0-9.]* ms (\([0-9.]*\) FPS).*/\1/p' "$err")
    full=$(sed -n 's/.*ms\/run (\([0-9.]*\) FPS).*/\1/p' "$err")
    awk -F, -v mol="$mol" -v n="$n" -v v="$v" -v gpu="$gpu" -v full="$full" 'NR == 2 {
        printf "| %s | %s^3 | %s | %.3f | %.3f | %.3f | %.2f | %s | %s | %s |\n",
               mol, n, v, $13, $14, $15, $16, gpu, full, $6 }' "$f"
done
