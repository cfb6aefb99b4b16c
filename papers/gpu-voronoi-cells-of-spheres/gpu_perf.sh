#!/bin/sh
# The device-tool run of the speed work: end-to-end GPU times at 100^2
# (first run = cold program cache, then the best of the warm runs), Table 1,
# and byte-identity of the certified output GPU / PoCL / --threads 1 against
# outputs of the reference backend computed beforehand (CARRY_DIR/expected,
# NAME.tsv per input at the default samples).
# Runs from the repository root with the carried build in $1; writes
# $OUT/gpu_perf.tgz.
# usage: gpu_perf.sh CARRY_DIR
carry=$1
[ -n "$OUT" ] || { echo "OUT not set" >&2; exit 1; }
here=papers/gpu-voronoi-cells-of-spheres
export LD_LIBRARY_PATH="$carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export XDG_CACHE_HOME=/tmp/vorball-perf-cache   # empty: the first run is cold
vorball=$carry/vorball
in=/tmp/vorball-perf-in
mkdir -p /etc/OpenCL/vendors
echo /usr/local/nvidia/lib64/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
{ "$vorball" devices; nvidia-smi -L; echo "cpus: $(nproc)"; grep -m1 'model name' /proc/cpuinfo; } \
    > "$OUT/devices.txt" 2>&1
sh "$here/prepare_inputs.sh" corpus/data "$in" 2> "$OUT/prepare.err"
# 1. Speed at 100^2: bench with the device opened once (stage times;
#    device_setup = that opening), bench --cold opening it for every run
#    (setup = OpenCL set-up on its own thread, setup_wait = what sampling
#    waited for it), then the process wall time of `vorball vertices`
#    (parsing and writing included).
for f in 1crn_apbs.xyzr 3pqr.xyzr; do
    timeout 60 "$vorball" bench --device gpu --samples 100 --repeat 5 --json "$in/$f" \
        > "$OUT/perf_${f%.*}.json" 2> "$OUT/perf_${f%.*}.err"
    timeout 60 "$vorball" bench --device gpu --samples 100 --repeat 3 --cold --json "$in/$f" \
        > "$OUT/perf_cold_${f%.*}.json" 2> "$OUT/perf_cold_${f%.*}.err"
    for k in 1 2 3; do
        t0=$(date +%s.%N)
        timeout 60 "$vorball" vertices --device gpu --samples 100 "$in/$f" > /tmp/v.tsv 2>/dev/null
        rc=$?
        t1=$(date +%s.%N)
        echo "$f vertices --samples 100 run $k: exit $rc wall $(awk -v a="$t0" -v b="$t1" \
            'BEGIN { printf "%.3f", b - a }') s" >> "$OUT/wall.txt"
    done
done
# 2. Byte-identity against the expected outputs.
id=$OUT/identity.txt
: > "$id"
for f in corpus/inputs/*.xyzr corpus/data/1crn.pdb "$in/1crn_apbs.xyzr" "$in/3pqr.xyzr"; do
    n=$(basename "$f")
    for run in gpu cpu gpu1; do
        case $run in
        gpu1) [ "$n" = 1crn_apbs.xyzr ] || [ "$n" = 3pqr.xyzr ] || continue
              set -- --device gpu --threads 1 ;;
        *) set -- --device $run ;;
        esac
        timeout 90 "$vorball" vertices "$@" "$f" > /tmp/v.tsv 2> "$OUT/v_${run}_$n.err"
        rc=$?
        if cmp -s /tmp/v.tsv "$carry/expected/$n.tsv"; then r="=="; else r="!="; fi
        echo "$n $run exit=$rc $r expected ($(grep -vc '^#' /tmp/v.tsv) lines)" >> "$id"
    done
done
# 3. Table 1 (one run per configuration, warm program cache).
timeout 120 sh "$here/run_bench.sh" "$vorball" gpu "$in" "$OUT/results" table1 2> "$OUT/table1.err"
# The device tool brings back few files: pack everything into one.
tar -C "$OUT" -czf /tmp/gpu_perf.tgz . && rm -rf "$OUT"/* && mv /tmp/gpu_perf.tgz "$OUT/"
