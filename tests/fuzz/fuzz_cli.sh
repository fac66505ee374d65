#!/usr/bin/env bash
# fuzz_cli.sh EXE FUZZ_PARSE [--src DIR] [--seed S] [--iterations N]
#             [--max-seconds T] [--known-raw LIST]
#
# Process-level mutation fuzzer of the `subspectra` binary EXE.  FUZZ_PARSE
# --write makes N mutants (seed S) of links, meshes and stencils; each is fed
# to the commands that read it, under `timeout`:
#   links     analyze --vertex - (and the link as an argument), enumerate
#             canonical (links that parse with more than 7 vertices only to
#             canonical, more than 64 are not written: they are slow by design)
#   meshes    subdivide --levels 1 (a random scheme and output format),
#             enumerate mesh, limit --gauss 1 -d
#   stencils  analyze --stencil at the tetrahedron link, check --vertices 4..4
# and every iteration also runs a command with one option set to a bad value
# (empty, -1, -0, nan, inf, 1e308, huge integers, control bytes, ...).
# Every run must exit 0, 1 or 2, not die of a signal or the timeout, print no
# sanitizer report, and say why on stderr when it exits 2; raw bytes (< 0x20
# or >= 0x7f, newline aside) on stderr fail too, unless the input's class is in
# --known-raw (link, mesh, stencil, options): a known bug, counted.
# A failure prints the seed, the iteration, the command and the input,
# escaped; `FUZZ_PARSE --seed S --only I --dump` prints the mutant again.
set -u
exe=$1
gen=$2
shift 2
src=$(cd "$(dirname "$0")/../.." && pwd)
seed=1
n=100
max_seconds=0
known=","
while [ $# -gt 0 ]; do
  case $1 in
  --src) src=$2 ;;
  --seed) seed=$2 ;;
  --iterations) n=$2 ;;
  --max-seconds) max_seconds=$2 ;;
  --known-raw) known=",$2," ;;
  *)
    echo "fuzz_cli.sh: unknown option '$1'" >&2
    exit 2
    ;;
  esac
  shift 2 || {
    echo "fuzz_cli.sh: $1 needs a value" >&2
    exit 2
  }
done

case $exe in /*) ;; *) exe=$PWD/$exe ;; esac
case $gen in /*) ;; *) gen=$PWD/$gen ;; esac
case $src in /*) ;; *) src=$PWD/$src ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/in" "$tmp/out"
cd "$tmp/out" || exit 2 # an output name that is a bad value lands here
if ! "$gen" --src "$src" --seed "$seed" --iterations "$n" --write "$tmp/in" >/dev/null; then
  echo "fuzz_cli.sh: $gen --write failed" >&2
  exit 2
fi

limit=$((20 * ${SS_TIMEOUT_MULTIPLIER:-1}))
RANDOM=$seed # bash's generator, seeded: the same choices on every run
runs=0
failures=0
raw_known=0
declare -A by_status=()
m=$src/data/meshes

# Escaped bytes of a file (at most 2000), as fz_escape writes them.
escaped() {
  head -c 2000 "$1" | LC_ALL=C od -An -v -tu1 | LC_ALL=C awk '{
    for (i = 1; i <= NF; i++) {
      c = $i + 0
      if (c == 92) printf "\\\\"; else if (c == 10) printf "\\n";
      else if (c == 9) printf "\\t"; else if (c == 13) printf "\\r";
      else if (c < 32 || c >= 127) printf "\\x%02x", c;
      else printf "%c", c
    } }'
}

# check CLASS ITER INPUT CMD...: run CMD with INPUT (a file, or /dev/null) on
# standard input and check the contract.
check() {
  local class=$1 iter=$2 input=$3
  shift 3
  runs=$((runs + 1))
  local rc why=""
  timeout -k 5 "$limit" "$@" <"$input" >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  by_status[$rc]=$((${by_status[$rc]:-0} + 1))
  if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
    why="no result within $limit s (a hang?)"
  elif [ "$rc" -gt 128 ]; then
    why="killed by signal $((rc - 128))"
  elif [ "$rc" -gt 2 ]; then
    why="exit status $rc (not 0, 1 or 2)"
  elif grep -Eq 'Sanitizer|runtime error:' "$tmp/stderr"; then
    why="sanitizer report"
  elif [ "$rc" -eq 2 ] && ! grep -q '[^[:space:]]' "$tmp/stderr"; then
    why="exit 2 without a message"
  elif [ -n "$(LC_ALL=C tr -d '\n\040-\176' <"$tmp/stderr" | head -c 1)" ]; then
    if [[ $known == *",$class,"* ]]; then
      raw_known=$((raw_known + 1))
    else
      why="raw bytes on stderr (escape them)"
    fi
  fi
  [ -z "$why" ] && return 0
  failures=$((failures + 1))
  {
    echo "FAILED: seed $seed iteration $iter ($class): $why"
    printf '  command:'
    printf ' %q' "$@"
    printf '\n'
    if [ "$input" != /dev/null ]; then
      echo "  input (stdin or file): \"$(escaped "$input")\""
      echo "  replay: $gen --seed $seed --only $iter --dump"
    fi
    echo "  stderr: \"$(head -c 1000 "$tmp/stderr" | escaped /dev/stdin)\""
  } >&2
}

pick() { # pick WORD...: one of the words
  local a=("$@")
  echo "${a[RANDOM % ${#a[@]}]}"
}

# Bad option values, and commands with a slot for one (cheap when the value is
# accepted: no value here makes a valid but long run).
bad_values=('' '-1' '0' '-0' '-0.0' 'nan' 'inf' '-inf' '1e308' '1e-320' '4..3'
  '0..0' '-5..-4' '1..99999999999' '99999999999999999999' '2147483648'
  '4294967296' '18446744073709551616' '0x10' '3abc' ' 3' '3 ' '--' '-' '1/0'
  $'\x01' $'\x1b[31m' $'\xc3\xa9' $'\xff' '%s%n%s' "$(printf 'x%.0s' {1..3000})")
templates=(
  'analyze --scheme @ --vertex tetrahedron'
  'analyze --scheme tetoct --vertex @'
  'analyze --scheme tetoct --edge @'
  'analyze --scheme catmull-clark --surface-vertex @'
  'analyze --scheme tetoct --vertex tetrahedron --tol @'
  'analyze --scheme mlca --vertex tetrahedron --depth @'
  'analyze --scheme mlca --vertex tetrahedron --ring-levels @'
  'analyze --scheme tetoct --vertex tetrahedron --eigenvalues @'
  'analyze --scheme tetoct --vertex tetrahedron --format @'
  'analyze --scheme boxspline --edge 3 --diagonals @'
  'analyze --stencil @ --vertex tetrahedron'
  'matrix --scheme tetoct --vertex tetrahedron --format mtx --ring @'
  'subdivide --scheme tetoct --levels @ M/cube-6tets.mesh -o O/o.mesh'
  'subdivide --scheme @ M/cube-6tets.mesh -o O/o.mesh'
  'subdivide --scheme tetoct M/cube-6tets.mesh -o @'
  'subdivide --scheme tetoct --format @ M/cube-6tets.mesh -o O/o.mesh'
  'limit --scheme mlca M/hexstar-icosahedron.mesh --at @'
  'limit --scheme mlca M/hexstar-icosahedron.mesh --gauss @'
  'limit --scheme mlca M/hexstar-icosahedron.mesh --samples @'
  'limit --scheme @ M/hexstar-icosahedron.mesh --gauss 1'
  'limit --scheme mlca M/hexstar-icosahedron.mesh --gauss 1 --format @'
  'enumerate links --count --vertices @'
  'enumerate links --vertices 4..6 --part @'
  'enumerate random --samples 1 --vertices @'
  'enumerate random --vertices 6 --samples 1 --seed @'
  'enumerate canonical --format @'
  'enumerate mesh @'
  'check D/tetoct.ini --vertices @'
  'check D/tetoct.ini --edges @'
  'tune D/tensor-family.ini --edges 4..4 --evals @ -o O/t.ini'
  'tune D/tensor-family.ini --edges 4..4 --evals 2 --keep @ -o O/t.ini'
  'tune D/tensor-family.ini --edges @ --evals 2 -o O/t.ini'
  '@'
  'analyze @'
)

# option ITER: one template, one bad value.
option() {
  local t=${templates[RANDOM % ${#templates[@]}]}
  local v=${bad_values[RANDOM % ${#bad_values[@]}]}
  local args=() w
  for w in $t; do
    case $w in
    @) args+=("$v") ;;
    M/*) args+=("$m/${w#M/}") ;;
    O/*) args+=("$tmp/out/${w#O/}") ;;
    D/*) args+=("$src/data/stencils/${w#D/}") ;;
    *) args+=("$w") ;;
    esac
  done
  check options "$1" /dev/null "$exe" "${args[@]}"
}

start=$SECONDS
stopped=""
for ((i = 0; i < n; i++)); do
  if [ "$max_seconds" -gt 0 ] && [ $((SECONDS - start)) -ge "$max_seconds" ]; then
    stopped=" (stopped by --max-seconds after $i iterations)"
    break
  fi
  for f in "$tmp/in/$(printf '%06d' "$i")".*; do
    [ -e "$f" ] || continue
    case $f in
    *.link)
      check link "$i" "$f" "$exe" analyze --scheme "$(pick tetoct mlca)" --vertex -
      check link "$i" "$f" "$exe" enumerate canonical
      if [ "$(wc -c <"$f")" -le 300 ]; then
        check link "$i" /dev/null "$exe" analyze --scheme tetoct --vertex "$(tr -d '\000' <"$f")"
      fi
      ;;
    *.link64)
      check link "$i" "$f" "$exe" enumerate canonical
      ;;
    *.mesh | *.obj)
      ext=${f##*.}
      cp "$f" "$tmp/m.$ext"
      check mesh "$i" "$f" "$exe" subdivide --scheme "$(pick mlca tetoct boxspline loop catmull-clark)" \
        --levels 1 "$tmp/m.$ext" -o "$tmp/out/o.$(pick mesh vtk obj)"
      check mesh "$i" "$f" "$exe" enumerate mesh "$tmp/m.$ext"
      check mesh "$i" "$f" "$exe" limit --scheme mlca --gauss 1 -d "$tmp/m.$ext"
      ;;
    *.ini)
      cp "$f" "$tmp/s.ini"
      check stencil "$i" "$f" "$exe" analyze --stencil "$tmp/s.ini" --vertex tetrahedron
      check stencil "$i" "$f" "$exe" check "$tmp/s.ini" --vertices 4..4 --edges 3..3
      ;;
    esac
  done
  option "$i"
done

statuses=""
for s in $(printf '%s\n' "${!by_status[@]}" | sort -n); do
  statuses+=" exit $s: ${by_status[$s]};"
done
echo "fuzz_cli: seed $seed, $n iterations, $runs runs in $((SECONDS - start)) s$stopped"
echo " ${statuses%;}"
[ "$raw_known" -gt 0 ] && echo "  $raw_known runs with raw bytes on stderr (known: --known-raw)"
echo "  failures: $failures"
[ "$failures" -eq 0 ] && [ "$runs" -gt 0 ]
