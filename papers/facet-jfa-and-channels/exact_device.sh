#!/bin/sh
# Issue 23 on the H200 host: the exact engine beside Facet-JFA and JFA+1.
# Run from the repository root with the built tree in build/ and $OUT set:
#     sh .proto/exact_device.sh   (or papers/facet-jfa-and-channels/exact_device.sh)
# Writes into $OUT (stops starting runs after 270 s; about 4 minutes):
#   device.txt            nvidia-smi -L and `vorball devices`
#   t3d_*.json / .err     vorball jfa -V exact,facet,jfa+1 --check --repeat 10:
#                         256^3 x 13,573 and x 100,000; 512^3 x 1,000 and x 100,000
#                         (uniform, rng 1); 512^3 with the atoms of 4yvs; 2D 4096^2
#                         x 100,000. time_ms = the algorithm on the device (mean),
#                         prep_ms = the host's seed grid (exact only), wrong/differ
#                         against the exact reference
#   fig/fig2d_*.json      the paper's Fig. 4 sweep (2D, 256^2 .. 4096^2, 10 .. 100,000
#                         uniform seeds, -V jfa,jfa+1,facet,exact --check --repeat 10)
#   fig/tables.md, fig/jfa_speedup.dat, fig/jfa_speedup.gp
#                         jfa_tables.py's table and the plot's data; here:
#                         gnuplot -e "dir='FILES_AT/fig'; device='NVIDIA H200'" FILES_AT/fig/jfa_speedup.gp
#   chan_P_N_V.csv / .err vorball channels --stats-file, --no-pore --repeat 3, per
#                         protein P of corpus/data, grid N = 128, 256, 512, --jfa V =
#                         exact, facet: ms_upload, ms_jfa, ms_masks, ms_analysis
#   prot_P_N.json         vorball jfa --protein P -n N -V exact,facet --repeat 10 (no
#                         --check): the work counts behind the channel stage
#   runs.tsv              name, exit status, wall ms of every run
#   summary.tsv           one row per run and variant (python3, standard library)
set -u
T0=$(date +%s)
: "${OUT:?set OUT}"
V=build/cli/vorball
D=corpus/data
P=papers/facet-jfa-and-channels
# QUICK=1 DEVICE=cpu: a smoke run of this script on small sizes (PoCL).
DEV=${DEVICE:-gpu}
A=256 B=512 C=4096 K=100000 G="128 256 512" F="256 512 1024 2048 4096"
[ -n "${QUICK:-}" ] && A=32 B=64 C=256 K=3000 G="32 64" F="256 512"
mkdir -p "$OUT/fig" /etc/OpenCL/vendors 2>/dev/null
[ -f /etc/OpenCL/vendors/nvidia.icd ] ||
    echo /usr/local/nvidia/lib64/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
export XDG_CACHE_HOME=/tmp/vb_exact_cache POCL_CACHE_DIR=/tmp/vb_exact_cache/pocl
mkdir -p "$XDG_CACHE_HOME"
{ nvidia-smi -L; "$V" devices; } > "$OUT/device.txt" 2>&1
: > "$OUT/runs.tsv"

# run NAME LIMIT_S ARGS...: one vorball call, stderr to $OUT/NAME.err.
run() {
    name=$1 lim=$2
    shift 2
    if [ $(($(date +%s) - T0)) -gt 270 ]; then
        printf '%s\tskipped\t0\n' "$name" >> "$OUT/runs.tsv"
        return
    fi
    s=$(date +%s%N)
    timeout "$lim" "$V" "$@" 2> "$OUT/$name.err"
    rc=$?
    printf '%s\t%s\t%s\n' "$name" "$rc" $((($(date +%s%N) - s) / 1000000)) >> "$OUT/runs.tsv"
}

# Warm the program cache (kernel builds off the clock of every later run).
run warm 60 jfa --device "$DEV" -d 3 -n 64 -k 100 -V exact,facet,jfa+1 -o /dev/null
run warm2d 60 jfa --device "$DEV" -d 2 -n 256 -k 100 -V exact,facet,jfa+1,jfa -o /dev/null

J="jfa --device $DEV --json --check -V exact,facet,jfa+1 --repeat 10"
run t3d_${A}_13573 40 $J -d 3 -n $A -k 13573 -o "$OUT/t3d_${A}_13573.json"
run t3d_${A}_$K 40 $J -d 3 -n $A -k $K -o "$OUT/t3d_${A}_$K.json"
run t3d_${B}_1000 60 $J -d 3 -n $B -k 1000 -o "$OUT/t3d_${B}_1000.json"
run t3d_${B}_$K 60 $J -d 3 -n $B -k $K -o "$OUT/t3d_${B}_$K.json"
run t3d_${B}_4yvs 60 $J -n $B --protein "$D/4yvs_ev71_capsid.cif" -o "$OUT/t3d_${B}_4yvs.json"
run t2d_${C}_$K 40 $J -d 2 -n $C -k $K -o "$OUT/t2d_${C}_$K.json"

# Channels: the JFA stage per protein and grid, exact and Facet-JFA.
for n in $G; do
    for f in 1crn.pdb 1chb_hole2.pdb 1grm_single_hole2.pdb 3pqr.pqr 4yvs_ev71_capsid.cif; do
        p=${f%%.*}
        for v in exact facet; do
            run "chan_${p}_${n}_$v" 40 channels "$D/$f" --device "$DEV" --grid "$n" --jfa "$v" \
                --no-pore --repeat 3 -o /dev/null --stats-file "$OUT/chan_${p}_${n}_$v.csv"
        done
    done
done

# Fig. 4 of the paper with the exact engine beside JFA+1 and Facet-JFA.
for n in $F; do
    for k in 10 100 1000 10000 100000; do
        run "fig/fig2d_n${n}_k${k}" 30 jfa --device "$DEV" --json --check -d 2 -n "$n" -k "$k" \
            -V jfa,jfa+1,facet,exact --repeat 10 -o "$OUT/fig/fig2d_n${n}_k${k}.json"
    done
done
python3 "$P/jfa_tables.py" "$OUT/fig" > "$OUT/fig/tables.md" 2> "$OUT/fig/tables.err"
cp "$P/jfa_speedup.gp" "$OUT/fig/"

# The work behind the channel stage (the 1chb question of issue 23).
for n in $G; do
    for f in 1chb_hole2.pdb 4yvs_ev71_capsid.cif 1grm_single_hole2.pdb; do
        p=${f%%.*}
        run "prot_${p}_$n" 30 jfa --device "$DEV" --json -V exact,facet --repeat 10 -n "$n" \
            --protein "$D/$f" -o "$OUT/prot_${p}_$n.json"
    done
done

python3 - "$OUT" <<'EOF'
import csv, glob, json, os, sys
out = sys.argv[1]
keys = ["time_ms", "time_ms_min", "gpu_ms", "prep_ms", "prep_transfer_ms", "m", "tiles",
        "tiles_uniform", "candidates", "survivors", "evals", "exact_voxels", "visited",
        "wrong", "differ", "max_err"]
rows = [["run", "variant", "dim", "n", "seeds"] + keys]
for path in sorted(glob.glob(os.path.join(out, "*.json")) + glob.glob(os.path.join(out, "fig", "*.json"))):
    name = os.path.relpath(path, out)[:-5]
    try:
        doc = json.load(open(path))
    except (OSError, ValueError):
        rows.append([name, "failed"])
        continue
    for r in doc.get("runs", []):
        rows.append([name, r["variant"], doc["dim"], doc["n"], doc["seeds"]] +
                    [r.get(k, "") for k in keys])
st = ["ms_upload", "ms_jfa", "ms_masks", "ms_analysis", "ms_total", "atoms", "channel_voxels",
      "channels"]
rows.append([])
rows.append(["run", "variant", "grid", "frames"] + st)
for path in sorted(glob.glob(os.path.join(out, "chan_*.csv"))):
    name = os.path.basename(path)[:-4]
    try:
        recs = list(csv.DictReader(open(path)))
    except OSError:
        recs = []
    parts = name.split("_")
    if not recs:
        rows.append([name, parts[-1], parts[-2], 0])
        continue
    r = recs[0]
    rows.append([name, parts[-1], parts[-2], len(recs)] + [r.get(k, "") for k in st])
with open(os.path.join(out, "summary.tsv"), "w") as f:
    for r in rows:
        f.write("\t".join(str(x) for x in r) + "\n")
EOF
echo "exact_device: $(($(date +%s) - T0)) s" >> "$OUT/runs.tsv"
cat "$OUT/runs.tsv"
