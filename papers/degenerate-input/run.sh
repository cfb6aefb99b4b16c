#!/usr/bin/env bash
# Issue 27 benchmark: degenerate inputs through `vorball vertices`, one process per
# input, each under a time limit; one TSV row per input (README.md in this folder).
#
# usage: run.sh VORBALL [CGAL_VORBALL|none] [options]
#   VORBALL        the vorball binary to measure (any build: before and after a change)
#   CGAL_VORBALL   a vorball built with CGAL whose `crosscheck --vertices OUT --time`
#                  judges each equal-radius output and times CGAL; `none` (default) skips it
# options:
#   --device D          cpu (default, PoCL) or ref (plain C), or gpu/auto
#   --timeout S         seconds per `vertices` run (default 120); a run past it is 'timeout'
#   --verify-timeout S  seconds per `verify --arcs` and per crosscheck (default: --timeout)
#   --machine NAME      names the table: results/NAME.tsv (default: the host name)
#   --only REGEX        only inputs whose set/name matches the extended REGEX
#   --song DIR          the fetched data set (default build/song2022 of the checkout: the
#                       repository's tree, *.txt and PROTEINSET/*.pdb)
#   --work DIR          generated inputs and vertex files (default build/degenerate-input)
#   --no-verify         skip `verify --arcs`
#   --no-skip           run every size; by default, once an input times out, the larger
#                       inputs of its family (same lattice and jitter, same Song set) are
#                       written as 'skipped' without running
#   --threads N         passed to vertices and verify (default: theirs, all CPUs)
# Files over 4 MiB that a fetched copy lacks are simply not there: the largest
# BALLCLOUD file present per radius ratio is used.
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

usage() { sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
[ $# -ge 1 ] || usage
case $1 in -h|--help) usage ;; esac
vorball=$1; shift
cgal=none
if [ $# -ge 1 ] && [ "${1#--}" = "$1" ]; then cgal=$1; shift; fi
device=cpu timeout_s=120 verify_s= machine=$(hostname -s 2>/dev/null || echo machine) only=
song=$root/build/song2022 work=$root/build/degenerate-input verify=1 skip=1 threads=
while [ $# -gt 0 ]; do
    case $1 in
    --device) device=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --verify-timeout) verify_s=$2; shift 2 ;;
    --machine) machine=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    --song) song=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --no-verify) verify=0; shift ;;
    --no-skip) skip=0; shift ;;
    --threads) threads=$2; shift 2 ;;
    *) echo "run.sh: unknown option $1" >&2; usage ;;
    esac
done
verify_s=${verify_s:-$timeout_s}
[ -x "$vorball" ] || { echo "run.sh: $vorball is not an executable" >&2; exit 2; }
vorball=$(cd "$(dirname "$vorball")" && pwd)/$(basename "$vorball")
if [ "$cgal" != none ]; then
    [ -x "$cgal" ] || { echo "run.sh: $cgal is not an executable" >&2; exit 2; }
    "$cgal" crosscheck --help > /dev/null 2>&1 || { echo "run.sh: $cgal has no crosscheck (built without CGAL?)" >&2; exit 2; }
fi
[ -x /usr/bin/time ] || { echo "run.sh: needs /usr/bin/time (GNU time)" >&2; exit 2; }
thr=()
[ -n "$threads" ] && thr=(--threads "$threads")

# Inputs: the generated crystals (crystals.py suite) and the converted Song sets.
mkdir -p "$work/inputs" "$work/out/$machine"
if [ ! -f "$work/inputs/cospherical-78-unequal.xyzr" ]; then
    python3 "$here/crystals.py" suite "$work/inputs" || exit 1
fi
have_song=0
if [ -d "$song/EXTREMESET" ]; then
    have_song=1
    if [ ! -d "$work/song-xyzr/EXTREMESET" ]; then
        python3 "$here/song2022_to_xyzr.py" "$song" "$work/song-xyzr" || exit 1
    fi
else
    echo "run.sh: no Song data set at $song (fetch it, see README.md): crystals only" >&2
fi

# by_size PATH...: the existing PATHs ordered by the number that ends their name (BALL_1_5_80000).
by_size() {
    for f in "$@"; do
        [ -f "$f" ] || continue
        b=$(basename "$f"); b=${b%.*}; echo "${b##*_} $f"
    done | sort -n | cut -d' ' -f2-
}

# The list: SET<TAB>FAMILY<TAB>PATH, in the order run; sizes grow within a family.
list=$work/out/$machine/inputs.list
{
    if [ $have_song = 1 ]; then
        s=$work/song-xyzr
        for f in "$s"/EXTREMESET/*.xyzr "$s"/ANOMALYSET/*.xyzr "$s"/VISUALSET/*.xyzr; do
            [ -f "$f" ] && printf '%s\t%s\t%s\n' "$(basename "$(dirname "$f")")" "$(basename "$f" .xyzr)" "$f"
        done
    fi
    for f in "$work"/inputs/cospherical-*.xyzr; do
        printf 'cospherical\t%s\t%s\n' "$(basename "$f" .xyzr)" "$f"
    done
    for kind in fcc bcc sc; do
        for tag in exact j1e-12 j1e-9 j1e-6 j1e-3 random; do
            for f in "$work"/inputs/$kind-*-$tag.xyzr; do
                [ -f "$f" ] || continue
                b=$(basename "$f"); b=${b#*-}; echo "${b%%-*} $f"
            done | sort -n | while read -r _ f; do
                printf '%s\t%s-%s\t%s\n' "$kind" "$kind" "$tag" "$f"
            done
        done
    done
    if [ $have_song = 1 ]; then
        by_size "$s"/BALLSMALLSET/*.xyzr | while read -r f; do
            printf 'BALLSMALLSET\tBALLSMALLSET\t%s\n' "$f"
        done
        for d in "$s"/BALLCLOUD/*/; do
            f=$(by_size "$d"*.xyzr | tail -1)
            [ -n "$f" ] && printf 'BALLCLOUD\t%s\t%s\n' "$(basename "$f" .xyzr)" "$f"
        done
        for f in "$song"/PROTEINSET/*.pdb; do
            [ -f "$f" ] && printf 'PROTEINSET\t%s\t%s\n' "$(basename "$f" .pdb)" "$f"
        done
    fi
} > "$list"

tsv=$here/results/$machine.tsv
mkdir -p "$here/results"
cpu=$(awk -F': ' '/^model name/ { print $2; exit }' /proc/cpuinfo 2> /dev/null)
{
    echo "# run.sh $vorball ($("$vorball" --version 2>&1 | head -1)), cgal: $cgal"
    echo "# machine $machine: $(nproc) CPUs, $cpu; $(date -u +%Y-%m-%dT%H:%MZ); load $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "# device $device, timeout ${timeout_s} s per vertices run, ${verify_s} s per verify/crosscheck"
    printf 'set\tinput\tballs\tdevice\tstatus\twall_s\tpeak_rss_kib\tvertices\tcomplete\tcover_quadruples\texact_evals\tarcs\tarcs_s\tcgal\tcgal_s\n'
} > "$tsv"

# stat NAME FILE: a --stats counter of the stderr FILE ('-' when absent).
stat() { awk -F '\t' -v k="$1" '$1 == k { v = $2 } END { print (v == "" ? "-" : v) }' "$2"; }
# balls PATH: spheres in an XYZR file, or atom records (water left out) in a PDB.
balls() {
    case $1 in
    *.pdb) awk '/^(ATOM|HETATM)/ && substr($0, 18, 3) != "HOH" { n++ } END { print n + 0 }' "$1" ;;
    *) grep -vc '^[[:space:]]*\(#\|$\)' "$1" ;;
    esac
}

declare -A stopped
while IFS=$'\t' read -r set family path; do
    name=$(basename "$path"); name=${name%.*}
    if [ -n "$only" ] && ! printf '%s/%s\n' "$set" "$name" | grep -Eq "$only"; then continue; fi
    n=$(balls "$path")
    row() { printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$set" "$name" "$n" "$device" "$@" >> "$tsv"; }
    if [ $skip = 1 ] && [ -n "${stopped[$family]:-}" ]; then
        row "skipped (${stopped[$family]} timed out)" - - - - - - - - - -
        echo "$set/$name: skipped" >&2
        continue
    fi
    out=$work/out/$machine/$name.tsv err=$work/out/$machine/$name.err tm=$work/out/$machine/$name.time
    rm -f "$out"
    /usr/bin/time -f '%e %M' -o "$tm" timeout "$timeout_s" \
        "$vorball" vertices "$path" --device "$device" --stats "${thr[@]}" -o "$out" 2> "$err"
    rc=$?
    read -r wall rss < <(tail -1 "$tm")
    complete=no vertices=- arcs=- arcs_s=- cgal_res=- cgal_s=-
    if [ $rc = 124 ]; then
        status=timeout wall=">$timeout_s"
        stopped[$family]=$name
    elif [ $rc != 0 ]; then
        status="error $rc ($(grep -o 'E[0-9]\+' "$err" | head -1))"
    else
        status=ok
    fi
    if [ $rc = 0 ] && [ -f "$out" ]; then
        vertices=$(grep -vc '^#' "$out")
        grep -q '^# complete:' "$out" && complete=yes
        if [ $verify = 1 ]; then
            /usr/bin/time -f '%e' -o "$tm.arcs" timeout "$verify_s" \
                "$vorball" verify "$path" "$out" --arcs "${thr[@]}" > "$out.arcs" 2>&1
            vrc=$?
            arcs_s=$(tail -1 "$tm.arcs")
            case $vrc in
            0) arcs=agree ;;
            124) arcs=timeout arcs_s=">$verify_s" ;;
            1) # the counts of the report: lines not certified, vertices added, arcs undecided
               arcs=$(awk '/^verify: / { bad = $2 - $5 }
                           /arcs:/ { for (i = 1; i <= NF; i++) { if ($i == "undecided;") u = $(i - 1)
                                     if ($i == "vertices" && $(i + 1) == "added;") a = $(i - 1) } }
                           END { printf "DISAGREE: %d not certified, %s added, %s undecided", bad, a, u }' "$out.arcs") ;;
            *) arcs="error $vrc" ;;
            esac
        fi
    fi
    if [ "$cgal" != none ]; then
        vfile=$out
        if [ "$status" != ok ]; then vfile=$work/out/$machine/empty.tsv; echo '# none' > "$vfile"; fi
        timeout "$verify_s" "$cgal" crosscheck "$path" --vertices "$vfile" --time > "$out.cgal" 2> "$out.cgal.err"
        crc=$?
        case $crc in
        0) cgal_res=identical ;;
        1) cgal_res=$([ "$status" = ok ] && echo different || echo "(no vorball file)") ;;
        10) cgal_res="unequal radii" ;;
        124) cgal_res=timeout ;;
        *) cgal_res="error $crc" ;;
        esac
        cgal_s=$(sed -n 's/.*CGAL \([0-9.]*\) s.*/\1/p' "$out.cgal.err" | head -1)
        cgal_s=${cgal_s:--}
    fi
    row "$status" "$wall" "$rss" "$vertices" "$complete" "$(stat cover_quadruples "$err")" \
        "$(stat exact_evals "$err")" "$arcs" "$arcs_s" "$cgal_res" "$cgal_s"
    echo "$set/$name: $status $wall s, $rss KiB, $vertices vertices, arcs $arcs" >&2
done < "$list"
echo "wrote $tsv" >&2
