#!/bin/sh
# Issue #19 on the device machine (16 cores, one GPU): says whether the host
# has an mpirun (else it uses the one carried in BUILD_DIR/openmpi, see
# prepare_carry.sh), then
#   cpu: strong_scaling.sh (vertices of the 211,440-sphere capsid and
#        channels of a 500-frame trajectory on 1..16 ranks, CPU only);
#   gpu: the split cover on the GPU: `vertices --device gpu` of the same
#        capsid on 1, 2 and 4 ranks sharing the one GPU (each rank opens
#        VORBALL_DEVICE_INDEX = its rank on the host, modulo one GPU), the
#        files compared byte for byte with one rank's, and `bench` times.
# Each step stays under the device's 10 minutes a command; STEPS picks them.
#
# usage: sh papers/mpi-scaling/device_mpi.sh BUILD_DIR OUTDIR
#   BUILD_DIR  an MPI build (cli/vorball) or a carried folder (prepare_carry.sh)
#   OUTDIR     cpu/ (strong_scaling.sh's table), gpu.tsv, gpu/ (runs), host.txt
# Environment: STEPS ("cpu gpu"), GPU_RANKS ("1 2 4"), GPU_INPUT (the tiled
# capsid strong_scaling.sh prepares, else made here); the rest as for
# strong_scaling.sh (CORES, RANKS, FRAMES, GRID, TILE, MPIRUN).
# Run from the repository root.
set -u
build=$1 out=$2
here=$(cd "$(dirname "$0")" && pwd)
[ -d corpus/data ] || { echo "device_mpi.sh: run from the repository root" >&2; exit 2; }
mkdir -p "$out/gpu" || exit 3
if [ -x "$build/vorball" ]; then vorball=$build/vorball; else vorball=$build/cli/vorball; fi
[ -x "$vorball" ] || { echo "device_mpi.sh: no vorball in $build" >&2; exit 2; }
[ -d "$build/lib" ] && export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
host=$out/host.txt
{
    echo "# $(hostname): $(nproc) cores; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
    if command -v mpirun > /dev/null 2>&1; then
        echo "mpirun on the host: $(command -v mpirun) ($(mpirun --version 2>&1 | head -1))"
    elif [ -d "$build/openmpi" ]; then
        echo "no mpirun on the host: the carried Open MPI of $build/openmpi"
    else
        echo "no mpirun on the host and none carried (prepare_carry.sh)"
    fi
    command -v nvidia-smi > /dev/null 2>&1 && nvidia-smi -L
} > "$host" 2>&1
cat "$host"
if [ -z "${MPIRUN:-}" ] && ! command -v mpirun > /dev/null 2>&1; then
    [ -d "$build/openmpi" ] || exit 2
    ompi_dir=$(cd "$build/openmpi" && pwd)
    . "$ompi_dir/env.sh"
fi
MPIRUN=${MPIRUN:-mpirun}
export MPIRUN
rc=0
for step in ${STEPS:-cpu gpu}; do
    case $step in
    cpu)
        sh "$here/strong_scaling.sh" "$build" "$out/cpu" || rc=$?
        ;;
    gpu)
        cap=$out/cpu/in/capsid8.xyzr
        if [ -n "${GPU_INPUT:-}" ]; then
            cap=$GPU_INPUT
            [ -s "$cap" ] || { echo "device_mpi.sh: no $cap" >&2; exit 2; }
        elif [ ! -s "$cap" ]; then
            mkdir -p "$out/cpu/in"
            python3 papers/gpu-voronoi-cells-of-spheres/cif_to_xyzr.py \
                corpus/data/4yvs_ev71_capsid.cif "$out/cpu/in/capsid.xyzr" &&
            python3 papers/gpu-voronoi-cells-of-spheres/tile_input.py "$out/cpu/in/capsid.xyzr" \
                ${TILE:-2 2 2} "$cap" || exit 3
        fi
        printf 'ranks\tbench_total_s\tcombine_s\tvertices\tend_to_end_s\tidentical\n' > "$out/gpu.tsv"
        first=
        for np in ${GPU_RANKS:-1 2 4}; do
            r=$out/gpu/$np
            "$MPIRUN" --allow-run-as-root --oversubscribe --bind-to none -np "$np" \
                -x OMPI_MCA_btl_vader_single_copy_mechanism=none \
                timeout 300 "$vorball" bench --device gpu --json "$cap" > "$r.json" 2> "$r.bench.err"
            t=$(sed -n 's/.*"total": \([0-9.]*\),.*/\1/p' "$r.json")
            c=$(sed -n 's/.*"combine": \([0-9.]*\),.*/\1/p' "$r.json")
            n=$(sed -n 's/.*"vertices": \([0-9]*\),.*/\1/p' "$r.json")
            s0=$(date +%s.%N)
            "$MPIRUN" --allow-run-as-root --oversubscribe --bind-to none -np "$np" \
                -x OMPI_MCA_btl_vader_single_copy_mechanism=none \
                timeout 300 "$vorball" vertices --device gpu "$cap" -o "$r.tsv" 2> "$r.err"
            e=$? s1=$(date +%s.%N)
            [ -n "$first" ] || first=$np
            same=no
            [ $e -eq 0 ] && cmp -s "$r.tsv" "$out/gpu/$first.tsv" && same=yes
            [ $e -eq 0 ] || { same="exit $e"; tail -3 "$r.err"; rc=1; }
            printf '%d\t%s\t%s\t%s\t%s\t%s\n' "$np" "${t:--}" "${c:-0}" "${n:--}" \
                "$(awk -v a="$s0" -v b="$s1" 'BEGIN { printf "%.3f", b - a }')" "$same" \
                >> "$out/gpu.tsv"
            tail -1 "$out/gpu.tsv"
        done
        # The vertex files are large; their identity is in the table.
        for np in ${GPU_RANKS:-1 2 4}; do
            [ "$np" = "$first" ] || rm -f "$out/gpu/$np.tsv"
        done
        rm -f "$out/gpu/$first.tsv"
        ;;
    *) echo "device_mpi.sh: unknown step '$step' (cpu, gpu)" >&2; exit 2 ;;
    esac
done
if command -v gnuplot > /dev/null 2>&1 && [ -s "$out/cpu/scaling.tsv" ]; then
    gnuplot -e "tsv='$out/cpu/scaling.tsv'; png='$out/scaling.png'" "$here/scaling.gp" || true
fi
exit $rc
