# reports/find-program.sh — sourced by the report scripts (exhaustive.sh,
# tuned.sh): sets `here` (the source tree, the folder above this one) and
# `exe`, the program: $SUBSPECTRA, else build/cli/subspectra of the source
# tree, else subspectra on PATH; exits 2 naming the script ($1) when none is
# executable.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
exe=${SUBSPECTRA:-}
if [[ -z $exe ]]; then
  if [[ -x $here/build/cli/subspectra ]]; then exe=$here/build/cli/subspectra
  else exe=$(command -v subspectra || true); fi
fi
[[ -n $exe && -x $exe ]] || { echo "$1: no subspectra program (set SUBSPECTRA)" >&2; exit 2; }
