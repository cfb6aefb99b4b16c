# Sourced by the fault scripts once $work is set: the pipeline helpers,
# $work made, and ASan's link-order check off (under ASan the shim comes
# first in the library list, before ASan's runtime).
here=$(cd "$(dirname "$0")" && pwd)
. "$here/../pipeline/lib.sh"
mkdir -p "$work" || fail "cannot create $work"
ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
export ASAN_OPTIONS
