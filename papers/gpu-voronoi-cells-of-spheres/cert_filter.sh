#!/bin/sh
# The certification filter on the device (issue #30): `vorball vertices` on
# each input and device with VORBALL_DEVICE_CERT=0 (the host certifier
# alone) and =1 (roots judged by gpu/cert_filter.cl, or the host twin for
# ref, first), REPEAT times each after one untimed run that fills the
# program caches. Per run: user and system CPU seconds, wall seconds, the
# load, and --stats' certify_after_s, judge_s and judged_vertex / _not /
# _open; the vertex files are compared byte for byte (provenance lines
# aside) with the first device's VORBALL_DEVICE_CERT=0 file.
# usage: cert_filter.sh VORBALL OUTDIR REPEAT "DEVICES" INPUT...
#   e.g. cert_filter.sh build/cli/vorball /tmp/cf 3 "gpu ref" capsid.xyzr
# THREADS (default: unset, every CPU) is passed as --threads.
set -u
[ $# -ge 5 ] || { sed -n '2,/^set -u/p' "$0" | sed '$d;s/^# \{0,1\}//'; exit 2; }
vorball=$1 out=$2 repeat=$3 devices=$4
shift 4
mkdir -p "$out" || exit 1
th=${THREADS:+--threads $THREADS}
for inp in "$@"; do
  b=$(basename "$inp"); b=${b%%.*}
  ref=
  for dev in $devices; do
    for mode in 0 1; do
      VORBALL_DEVICE_CERT=$mode "$vorball" vertices --device "$dev" $th --quiet "$inp" \
        -o /dev/null 2>/dev/null
      i=0
      while [ $i -lt "$repeat" ]; do
        i=$((i + 1))
        f="$out/$b.$dev.$mode"
        /usr/bin/time -f "%U %S %e" -o "$f.time" env VORBALL_DEVICE_CERT=$mode "$vorball" \
          vertices --device "$dev" $th --quiet --stats "$inp" -o "$f.tsv" 2>"$f.stats"
        printf '%s\t%s\tcert=%s\tuser_sys_wall=%s\tload=%s\t%s\n' "$b" "$dev" "$mode" \
          "$(cat "$f.time")" "$(cut -d' ' -f1 /proc/loadavg)" \
          "$(grep -E '^(certify_after_s|judge_s|judged_vertex|judged_not|judged_open)' \
             "$f.stats" | tr '\t\n' '= ')"
        grep -v '^#' "$f.tsv" >"$f.body"
        [ -n "$ref" ] || ref="$f.body"
        cmp -s "$ref" "$f.body" || echo "$b $dev cert=$mode: DIFFERENT from $ref"
      done
    done
  done
done
