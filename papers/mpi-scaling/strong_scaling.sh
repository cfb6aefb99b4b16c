#!/bin/sh
# Strong scaling of `vorball` over MPI ranks on one CPU host: the certified
# vertices of the tiled 211,440-atom capsid with ranks x threads = the host's
# cores (16 on the lead's device machine), and the channels of a 500-frame
# trajectory synthesized from the corpus's 51-frame MD file, one rank per
# core (the channel reference engine runs one thread). Every rank count's
# output is compared with one rank's, byte for byte. About 3 minutes on 16
# cores.
#
# usage: sh papers/mpi-scaling/strong_scaling.sh BUILD_DIR OUTDIR
#   BUILD_DIR  a build with -DVORBALL_WITH_MPI=ON (cli/vorball in it), or a
#              carried folder with vorball, lib/ and, where the host has no
#              Open MPI, openmpi/ (carry_openmpi.sh)
#   OUTDIR     scaling.tsv (the table), scaling.txt (what was printed), runs/
# Environment: CORES (default nproc), RANKS ("1 2 4 8 16"; counts that do not
# divide CORES are skipped), FRAMES (500), GRID (64), TILE (the capsid's
# copies per axis, "2 2 2"), MPIRUN (mpirun from PATH, else the carried one),
# WORKLOADS ("vertices channels": which of the two run).
# Run from the repository root.
# Plot (here, with gnuplot): gnuplot -e "tsv='OUTDIR/scaling.tsv'; png='x.png'" \
#   papers/mpi-scaling/scaling.gp
set -u
build=$1 out=$2
[ -d corpus/data ] || { echo "strong_scaling.sh: run from the repository root" >&2; exit 2; }
mkdir -p "$out/in" "$out/runs" || exit 3
if [ -x "$build/vorball" ]; then vorball=$build/vorball; else vorball=$build/cli/vorball; fi
[ -x "$vorball" ] || { echo "strong_scaling.sh: no vorball in $build" >&2; exit 2; }
[ -d "$build/lib" ] && export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
if [ -z "${MPIRUN:-}" ] && ! command -v mpirun > /dev/null 2>&1 && [ -d "$build/openmpi" ]; then
    ompi_dir=$(cd "$build/openmpi" && pwd)
    . "$ompi_dir/env.sh"
fi
MPIRUN=${MPIRUN:-mpirun}
command -v "$MPIRUN" > /dev/null 2>&1 ||
    { echo "strong_scaling.sh: no $MPIRUN (install Open MPI, or carry_openmpi.sh)" >&2; exit 2; }
cores=${CORES:-$(nproc)}
frames=${FRAMES:-500}
grid=${GRID:-64}
ranks=${RANKS:-"1 2 4 8 16"}
tile=${TILE:-"2 2 2"}
export OMPI_MCA_btl_vader_single_copy_mechanism=none
# Unbound ranks with THREADS threads each (what vorball takes by default
# under mpirun: cores / ranks on the host; set here so the table says it).
mpi() { # NP THREADS CMD...
    np=$1 th=$2
    shift 2
    "$MPIRUN" --allow-run-as-root --oversubscribe --bind-to none -np "$np" \
        -x VORBALL_THREADS="$th" -x POCL_MAX_PTHREAD_COUNT="$th" -x OMPI_MCA_btl_vader_single_copy_mechanism "$@"
}
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.3f", b - a }'; }
start=$(now)
txt=$out/scaling.txt
tsv=$out/scaling.tsv
: > "$txt"
say() { echo "$*" | tee -a "$txt"; }
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
say "# $(hostname): $cores cores ($cpu); $("$vorball" --version); $("$MPIRUN" --version 2>&1 | head -1)"
t=$(now)
python3 papers/gpu-voronoi-cells-of-spheres/cif_to_xyzr.py corpus/data/4yvs_ev71_capsid.cif \
    "$out/in/capsid.xyzr" 2> "$out/in/prep.err" &&
python3 papers/gpu-voronoi-cells-of-spheres/tile_input.py "$out/in/capsid.xyzr" $tile \
    "$out/in/capsid8.xyzr" 2>> "$out/in/prep.err" &&
python3 papers/facet-jfa-and-channels/synth_trajectory.py corpus/data/ngl_md_ascii_trj.pdb \
    "$frames" "$out/in/traj.pdb" 2>> "$out/in/prep.err" ||
    { cat "$out/in/prep.err" >&2; exit 3; }
cap=$out/in/capsid8.xyzr trj=$out/in/traj.pdb
say "# inputs in $(since "$t") s: $(grep -c . "$cap") spheres; $frames frames, grid $grid"
printf 'benchmark\tranks\tthreads\tseconds\tspeedup\tefficiency\tidentical\tnote\n' > "$tsv"
row() { # benchmark ranks threads seconds base_seconds base_ranks identical note
    awk -v b="$1" -v n="$2" -v th="$3" -v t="$4" -v t1="$5" -v n1="$6" -v s="$7" -v note="$8" 'BEGIN {
        sp = t1 / t
        # vertices: the cores stay fixed (ranks x threads), the ideal speedup
        # is 1; channels: one core a rank, the ideal is ranks / base ranks.
        ideal = b == "vertices" ? 1 : n / n1
        printf "%s\t%d\t%d\t%.3f\t%.3f\t%.3f\t%s\t%s\n", b, n, th, t, sp, sp / ideal, s, note }' >> "$tsv"
    say "$(tail -1 "$tsv")"
}

# 1. Vertices: bench times a run from a barrier to rank 0's merged vertices
# (input reading apart); `vertices -o` end to end at the first and last
# rank counts, whose files must be the same bytes.
workloads=${WORKLOADS:-vertices channels}
first= last=
for np in $ranks; do
    case " $workloads " in *" vertices "*) ;; *) break ;; esac
    [ $((cores % np)) -eq 0 ] || continue
    th=$((cores / np)) r=$out/runs/bench.$np
    mpi "$np" "$th" timeout 600 "$vorball" bench --device ref --json "$cap" > "$r.json" 2> "$r.err"
    t=$(sed -n 's/.*"total": \([0-9.]*\),.*/\1/p' "$r.json")
    n=$(sed -n 's/.*"vertices": \([0-9]*\),.*/\1/p' "$r.json")
    c=$(sed -n 's/.*"combine": \([0-9.]*\),.*/\1/p' "$r.json")
    if [ -z "$t" ]; then say "vertices on $np ranks failed: $(tail -3 "$r.err")"; continue; fi
    [ -n "$first" ] || { first=$np; t1=$t; n1=$n; }
    last=$np
    same=no
    [ "$n" = "$n1" ] && same=count
    row vertices "$np" "$th" "$t" "$t1" "$first" "$same" "$n vertices; gather+merge ${c:-0} s"
done
for np in $first $last; do
    [ -n "$np" ] || continue
    th=$((cores / np)) r=$out/runs/vertices.$np
    t=$(now)
    mpi "$np" "$th" timeout 600 "$vorball" vertices --device ref --stats "$cap" -o "$r.tsv" 2> "$r.err"
    say "# vertices end to end on $np ranks x $th threads: exit $?, $(since "$t") s (mpirun, reading, writing $(wc -c < "$r.tsv") bytes)"
done
if [ -n "$first" ] && [ "$first" != "$last" ]; then
    if cmp -s "$out/runs/vertices.$first.tsv" "$out/runs/vertices.$last.tsv"; then
        say "# vertex files on $first and $last ranks: identical"
    else
        say "# vertex files on $first and $last ranks: DIFFERENT"
    fi
fi
rm -f "$out/runs/vertices."*.tsv

# 2. Channels: frames dealt round-robin, one rank per core, end to end.
first=
for np in $ranks; do
    case " $workloads " in *" channels "*) ;; *) break ;; esac
    [ "$np" -le "$cores" ] || continue
    r=$out/runs/channels.$np
    t=$(now)
    mpi "$np" 1 timeout 600 "$vorball" channels --device ref --grid "$grid" "$trj" -o "$r.csv" \
        --stats-file "$r.stats" 2> "$r.err"
    rc=$? t=$(since "$t")
    if [ $rc -ne 0 ]; then say "channels on $np ranks failed (exit $rc): $(tail -3 "$r.err")"; continue; fi
    [ -n "$first" ] || { first=$np; t1=$t; }
    cut -d, -f1-12 "$r.stats" > "$r.cut"
    same=no
    cmp -s "$r.csv" "$out/runs/channels.$first.csv" && cmp -s "$r.cut" "$out/runs/channels.$first.cut" && same=yes
    row channels "$np" 1 "$t" "$t1" "$first" "$same" "$(sed -n 's/.*; \([0-9.]* frames\/s\).*/\1/p' "$r.err")"
done
say "# done in $(since "$start") s; the table is $tsv"
