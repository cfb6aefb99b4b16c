#!/bin/sh
# The one device-tool run: Table 1 and Fig. 13 on the GPU, and the
# byte-identity of certified output GPU vs PoCL (CPU) vs reference backend.
# Runs from the repository root with the carried build in $1; writes $OUT.
# usage: gpu_batch.sh CARRY_DIR
carry=$1
[ -n "$OUT" ] || { echo "OUT not set" >&2; exit 1; }
here=papers/gpu-voronoi-cells-of-spheres
export LD_LIBRARY_PATH="$carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
vorball=$carry/vorball
mkdir -p /etc/OpenCL/vendors
echo /usr/local/nvidia/lib64/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
"$vorball" devices > "$OUT/devices.txt" 2>&1
nvidia-smi -L >> "$OUT/devices.txt" 2>&1
sh "$here/prepare_inputs.sh" corpus/data "$OUT/in" 2> "$OUT/prepare.err"
# Identity first (small, decisive), then the timings.
id=$OUT/identity.txt
: > "$id"
for f in corpus/inputs/*.xyzr "$OUT/in/1crn.pdb" "$OUT/in/1crn_apbs.xyzr" "$OUT/in/3pqr.xyzr"; do
    n=$(basename "$f")
    for d in gpu cpu ref; do
        [ $d = ref ] && [ "$n" = 3pqr.xyzr ] && continue
        timeout 60 "$vorball" vertices --device $d --stats "$f" > "$OUT/v_${d}_$n.tsv" 2> "$OUT/v_${d}_$n.err"
        echo "$n $d exit=$?" >> "$id"
    done
    if cmp -s "$OUT/v_gpu_$n.tsv" "$OUT/v_cpu_$n.tsv"; then echo "$n gpu==cpu" >> "$id"; else echo "$n gpu!=cpu" >> "$id"; fi
    [ -f "$OUT/v_ref_$n.tsv" ] && { cmp -s "$OUT/v_gpu_$n.tsv" "$OUT/v_ref_$n.tsv" && echo "$n gpu==ref" >> "$id" || echo "$n gpu!=ref" >> "$id"; }
done
timeout 200 sh "$here/run_bench.sh" "$vorball" gpu "$OUT/in" "$OUT/results" table1 2> "$OUT/table1.err"
timeout 150 sh "$here/run_bench.sh" "$vorball" gpu "$OUT/in" "$OUT/results" fig13 2> "$OUT/fig13.err"
# Few files come back from the device tool: pack everything into one.
rm -rf "$OUT/in"
tar -C "$OUT" -czf /tmp/gpu_batch.tgz . && rm -rf "$OUT"/* && mv /tmp/gpu_batch.tgz "$OUT/"
