#!/bin/sh
# The fixed cost of `vorball vertices` on a GPU machine (issue #30): the whole
# process on a 327-atom protein with --device auto (host threads below the
# crossover, see crossover.sh), gpu and ref, REPEAT warm runs each after one
# untimed run that fills the program cache; and the GPU memory the process
# holds at its peak (nvidia-smi polled every 20 ms) on the inputs given.
# usage: fixed_cost.sh VORBALL OUTDIR REPEAT PROTEIN [INPUT...]
# OUTDIR/fixed_cost.tsv: input, device, best and median wall seconds, the
# backend --stats names; OUTDIR/gpu_memory.tsv: input, atoms, peak MiB used
# by the process on the GPU (0 when nvidia-smi saw none) and the MiB of device
# buffers vorball counted (--stats device_bytes_peak; without the driver's own
# context). VORBALL_DEVICE_MEMORY_MIB in the environment caps the budget.
set -u
[ $# -ge 4 ] || { sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'; exit 2; }
vorball=$1 out=$2 repeat=$3 protein=$4
shift 4
mkdir -p "$out" || exit 1
printf 'input\tdevice\tbest_s\tmedian_s\tbackend\n' > "$out/fixed_cost.tsv"
"$vorball" vertices --quiet --device gpu "$protein" -o "$out/warm.tsv" 2> /dev/null
for dev in auto gpu ref; do
    : > "$out/times"
    r=1
    while [ "$r" -le "$repeat" ]; do
        s=$(date +%s.%N)
        "$vorball" vertices --quiet --stats --device "$dev" "$protein" -o "$out/$dev.tsv" 2> "$out/$dev.err"
        e=$(date +%s.%N)
        echo "$s $e" | awk '{printf "%.4f\n", $2 - $1}' >> "$out/times"
        r=$((r + 1))
    done
    cmp -s "$out/warm.tsv" "$out/$dev.tsv" || echo "NOTE: $dev output differs from the gpu's" >&2
    backend=$(grep '^backend' "$out/$dev.err" | cut -f2)
    sort -n "$out/times" | awk -v f="$(basename "$protein")" -v d="$dev" -v b="$backend" \
        '{v[NR] = $1} END {printf "%s\t%s\t%.4f\t%.4f\t%s\n", f, d, v[1], v[int((NR + 1) / 2)], b}' \
        >> "$out/fixed_cost.tsv"
done
printf 'input\tatoms\tpeak_gpu_mib\tdevice_bytes_peak_mib\n' > "$out/gpu_memory.tsv"
for in in "$protein" "$@"; do
    "$vorball" vertices --quiet --stats --device gpu --atoms "$out/mem.atoms" "$in" \
        -o "$out/mem.tsv" 2> "$out/mem.err" &
    pid=$!
    peak=0
    while kill -0 "$pid" 2> /dev/null; do
        m=$(nvidia-smi --query-compute-apps=pid,used_memory --format=csv,noheader,nounits 2> /dev/null |
            awk -F', *' -v p="$pid" '$1 == p {print $2}')
        [ -n "$m" ] && [ "$m" -gt "$peak" ] && peak=$m
        sleep 0.02
    done
    wait "$pid"
    atoms=$(sed -n 's/^# vorball atoms: .*, \([0-9]*\) spheres$/\1/p' "$out/mem.atoms")
    counted=$(awk -F'\t' '$1 == "device_bytes_peak" {printf "%.1f", $2 / 1048576}' "$out/mem.err")
    printf '%s\t%s\t%s\t%s\n' "$(basename "$in")" "$atoms" "$peak" "$counted" >> "$out/gpu_memory.tsv"
done
rm -f "$out/times" "$out/mem.tsv" "$out/mem.atoms" "$out/mem.err" "$out"/*.err
cat "$out/fixed_cost.tsv" "$out/gpu_memory.tsv"
