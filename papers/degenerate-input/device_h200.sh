#!/bin/sh
# The issue-27 measurements on a GPU host with no build tools: vorball (a build
# carried in CARRY: CARRY/vorball and CARRY/lib/, as papers/mpi-scaling/
# prepare_carry.sh packs it, any build) on degenerate inputs, beside their
# random counterparts, and the byte identity of the GPU's output with the
# corpus goldens. Runs from the repository root; writes $OUT (or OUTDIR).
#   CARRY/song/*.xyzr   Song 2022 sets converted by song2022_to_xyzr.py (optional)
# usage: sh papers/degenerate-input/device_h200.sh CARRY [OUTDIR]
set -u
carry=$1
out=${2:-${OUT:-}}
[ -n "$out" ] || { echo "device_h200.sh: no OUTDIR and OUT not set" >&2; exit 2; }
here=papers/degenerate-input
export LD_LIBRARY_PATH="$carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
vorball=$carry/vorball
if [ ! -f /etc/OpenCL/vendors/nvidia.icd ] && [ -e /usr/local/nvidia/lib64/libnvidia-opencl.so.1 ]; then
    mkdir -p /etc/OpenCL/vendors
    echo /usr/local/nvidia/lib64/libnvidia-opencl.so.1 > /etc/OpenCL/vendors/nvidia.icd
fi
in=/tmp/degenerate-inputs
mkdir -p "$in" "$out"
{ "$vorball" devices; nvidia-smi -L; nproc; } > "$out/device.txt" 2>&1

# 1. the corpus through the GPU: every golden's vertex lines, byte for byte
: > "$out/identity.txt"
for f in corpus/inputs/*.xyzr; do
    c=$(basename "$f" .xyzr)
    timeout 60 "$vorball" vertices --device gpu "$f" -o "$in/$c.gpu.tsv" 2> "$in/$c.gpu.err"
    rc=$?
    grep -v '^#' "$in/$c.gpu.tsv" > "$in/a" 2> /dev/null
    grep -v '^#' "corpus/golden/$c.tsv" > "$in/b"
    if [ $rc -eq 0 ] && cmp -s "$in/a" "$in/b"; then echo "$c gpu==golden"; else echo "$c gpu!=golden exit=$rc"; fi
done >> "$out/identity.txt" 2>&1

# 2. inputs: fcc crystals near 10^5 balls exact and jittered, their random
# counterparts, cospherical balls, and the Song sets carried along
python3 "$here/crystals.py" lattice fcc 29 -o "$in/fcc29.xyzr"
python3 "$here/crystals.py" lattice fcc 29 --jitter 1e-9 -o "$in/fcc29_j1e-9.xyzr"
python3 "$here/crystals.py" random fcc 29 -o "$in/fcc29_random.xyzr"
python3 "$here/crystals.py" lattice fcc 7 -o "$in/fcc7.xyzr"
python3 "$here/crystals.py" random fcc 7 -o "$in/fcc7_random.xyzr"
python3 "$here/crystals.py" cospherical 78 -o "$in/cospherical78.xyzr"
[ -d "$carry/song" ] && cp "$carry"/song/*.xyzr "$in/"

# 3. per input: bench (best of 3, the device opened once) and the whole
# process (wall, peak RSS), the vertex count and the completeness header
tsv=$out/h200.tsv
printf 'input\tspheres\tvertices\tcomplete\tbench_total_s\tcover_s\tcertify_s\tprocess_s\tpeak_rss_kb\tcover_quadruples\texact_evals\n' > "$tsv"
for f in "$in"/*.xyzr; do
    c=$(basename "$f" .xyzr)
    n=$(grep -vc '^#' "$f")
    timeout 90 "$vorball" bench --device gpu --repeat 3 --json "$f" > "$in/$c.bench.json" 2> "$in/$c.bench.err"
    set -- $(python3 -c "import json,sys
try:
    r = json.load(open(sys.argv[1]))[0]
    print(r['total'], r['envelope'], r['certification'])
except Exception:
    print('- - -')" "$in/$c.bench.json")
    total=$1 cover=$2 cert=$3
    /usr/bin/time -f '%e %M' -o "$in/$c.time" timeout 120 "$vorball" vertices --device gpu --stats "$f" \
        -o "$in/$c.tsv" 2> "$in/$c.err"
    # time(1) puts "Command exited with non-zero status N" first when it failed
    wall=$(tail -n 1 "$in/$c.time" | cut -d' ' -f1) rss=$(tail -n 1 "$in/$c.time" | cut -d' ' -f2)
    grep -q 'status 124' "$in/$c.time" && wall=timeout
    nv=$(grep -vc '^#' "$in/$c.tsv" 2> /dev/null)
    comp=no
    grep -q '^# complete: ' "$in/$c.tsv" 2> /dev/null && comp=yes
    nq=$(awk '$1 == "cover_quadruples" { print $2 }' "$in/$c.err")
    ne=$(awk '$1 == "exact_evals" { print $2 }' "$in/$c.err")
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$c" "$n" "$nv" "$comp" "$total" "$cover" \
        "$cert" "$wall" "$rss" "$nq" "$ne" >> "$tsv"
done
# 4. the same bytes on the host threads for the crystal (the reference backend)
timeout 200 "$vorball" vertices --device ref "$in/fcc29.xyzr" -o "$in/fcc29.ref.tsv" 2> /dev/null
if cmp -s "$in/fcc29.tsv" "$in/fcc29.ref.tsv"; then echo "fcc29 gpu==ref"; else echo "fcc29 gpu!=ref"; fi \
    >> "$out/identity.txt"
cat "$tsv"
