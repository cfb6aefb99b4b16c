#!/bin/bash
# Channels not in the HOLE examples, at vorball's defaults beside HOLE 2 with
# the same radius file (issue 32): vorball finds the axis; HOLE sweeps that
# axis (cvect = vorball's axis, cpoint = its start) and leaves out what
# vorball left out (water; the ligands of W811, the membrane of W809).
# CPU = user + sys.
#
# usage: more_2core.sh HOLE_DIR VORBALL OUTDIR PDB...
#   HOLE_DIR  a HOLE 2 checkout built apart (exe/hole, rad/simple.rad)
#   PDB       structures kept out of the repository (public PDB entries;
#             more_2core.md names them and where they were found)
# Writes OUTDIR/more_2core.tsv: name, HOLE's minimum radius per seed (1 2 3),
# HOLE's CPU seconds (seed 1), vorball's bottleneck, axis source, the axis,
# vorball's CPU seconds, and the W810 line.
set -u
[ $# -ge 4 ] || { sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
HD=$1 V=$2 OUT=$3
shift 3
mkdir -p "$OUT" || exit 3
cpu() { tail -1 "$1" | awk '{ printf "%.2f", $1 + $2 }'; }
printf 'name\thole_seed1\thole_seed2\thole_seed3\thole_cpu_s\tvorball\taxis\tu\tvorball_cpu_s\tw810\n' \
    > "$OUT/more_2core.tsv"
for pdb in "$@"; do
    name=$(basename "$pdb" .pdb)
    cp "$pdb" "$OUT/$name.pdb"
    (
        cd "$OUT" || exit 3
        /usr/bin/time -f '%U %S' -o "$name.vtime" "$V" channels --radii "$HD/rad/simple.rad" \
            --json -o "$name.json" "$name.pdb" 2> "$name.err"
        read -r v src u cv cp < <(python3 -c "import json,sys; f=json.load(open(sys.argv[1]))['frames'][0]; p=f.get('pore')
print('%.3f %s %s %s %s' % (f['channels'][0]['bottleneck_A'], p['axis_from'], ','.join('%.4f' % x for x in p['axis']),
      ' '.join(map(str, p['axis'])).replace(' ', '_'), ' '.join(map(str, p['start'])).replace(' ', '_')) if p else 'none none none none none')" "$name.json")
        lig=$(sed -En 's/.*W8(11|09): .*\): (.*)$/\2/p' "$name.err" | sed -E 's/ [0-9]+(,|$)//g' | tr '\n' ' ')
        w810=$(sed -n 's/.*W810: [^:]*: //p' "$name.err")
        h=()
        for seed in 1 2 3; do
            { printf '%s\n' "coord $name.pdb" "radius $HD/rad/simple.rad" "raseed $seed" \
                  "ignore HOH WAT $lig"
              [ "$cv" != none ] && printf '%s\n' "cvect ${cv//_/ }" "cpoint ${cp//_/ }"; } > "${name}_$seed.inp"
            /usr/bin/time -f '%U %S' -o "${name}_$seed.time" "$HD/exe/hole" < "${name}_$seed.inp" \
                > "${name}_$seed.out" 2> /dev/null
            rm -f sr_gseed_tempfile
            h+=("$(awk '/Minimum radius found/ { print $4 }' "${name}_$seed.out")")
        done
        printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "${h[0]}" "${h[1]}" "${h[2]}" \
            "$(cpu "${name}_1.time")" "$v" "$src" "$u" "$(cpu "$name.vtime")" "$w810" >> more_2core.tsv
    )
done
cat "$OUT/more_2core.tsv"
