#!/usr/bin/env bash
# test_convention.sh EXE SRCDIR — one command-line convention across the
# commands (issue 40):
#  - `subspectra help CMD [WHAT]` prints exactly what `CMD [WHAT] --help` prints,
#    for every command the overview lists (and enumerate's WHATs); an unknown
#    command is exit 2 with a message;
#  - wherever a command takes one of the long options --output, --scheme,
#    --jobs, --quiet it takes the short one (-o, -s, -j, -q) too, and its --help
#    lists the pair as "-X, --LONG";
#  - the short option reaches the same place as the long one (its value is
#    the one named in messages and gives the same output);
#  - analyze -o FILE and sweep --progress / --quiet;
#  - --progress in jsr, limit and deform (phase lines with it, none without);
#  - enumerate random has no -s (it was its seed; -s is --scheme elsewhere);
#  - every command writes JSON with one json-c setting: '/' not escaped;
#  - messages start "subspectra COMMAND: " (sweep's and merge's progress and
#    summaries too) and name nothing twice ("draw: draw:", "cell 1: ... cell 1:").
set -u
exe=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/../ss_expect.sh"

# ---- the commands, from the overview itself (a new command is covered) ----
mapfile -t cmds < <("$exe" help | sed -n '/^commands:/,/^$/p' | awk 'NF > 1 {print $1}')
[ "${#cmds[@]}" -ge 13 ] || fail "overview lists ${#cmds[@]} commands: ${cmds[*]}"
mapfile -t whats < <("$exe" enumerate --help | awk '/^  [a-z]+ / {print $1}')
[ "${#whats[@]}" -ge 4 ] || fail "enumerate lists ${#whats[@]} sub-commands"
all=("${cmds[@]}")
for w in "${whats[@]}"; do all+=("enumerate $w"); done

# ---- help CMD == CMD --help ----
cmp_help() { # cmp_help CMD [WHAT]
  checks=$((checks + 1))
  local a b ra rb
  a=$("$exe" help "$@" 2>&1)
  ra=$?
  b=$("$exe" "$@" --help 2>&1)
  rb=$?
  if [ "$ra" -ne 0 ] || [ "$rb" -ne 0 ] || [ "$a" != "$b" ] || [ -z "$a" ]; then
    fail "help $* (status $ra) differs from $* --help (status $rb)"
  fi
}
for c in "${all[@]}"; do
  # shellcheck disable=SC2086  # "enumerate links": two words
  cmp_help $c
done
expect 0 "^commands:" "$exe" help
[ "$("$exe" help)" = "$("$exe" --help)" ] || fail "help differs from --help"
[ "$("$exe" help --help)" = "$("$exe" --help)" ] || fail "help --help differs from --help"
expect 2 "subspectra help: unknown command 'frobnicate'" "$exe" help frobnicate
expect 2 "subspectra help: too many arguments" "$exe" help analyze extra
expect 2 "unknown 'enumerate bogus'" "$exe" help enumerate bogus

# ---- the short options ----
# For each command and pair: does the command take --LONG?  (--LONG=v or
# --LONG, then an unknown option: parsing stops at the first error, so
# nothing runs; a command without --LONG names --LONG.)  If it does, -X must
# be taken too (the error then names the bogus option, not -X) and --help
# must list "-X, --LONG".
pairs="o:output:1 s:scheme:1 j:jobs:1 q:quiet:"
taken=0
for c in "${all[@]}"; do
  for p in $pairs; do
    IFS=: read -r short long val <<<"$p"
    # shellcheck disable=SC2086
    if [ -n "$val" ]; then
      lout=$("$exe" $c "--$long=$val" --zz-bogus 2>&1)
      sargs=("-$short" "$val")
    else
      lout=$("$exe" $c "--$long" --zz-bogus 2>&1)
      sargs=("-$short")
    fi
    # the command has no --LONG (enumerate itself: no options but --help)
    grep -q -- "'--$long\|unknown 'enumerate --" <<<"$lout" && continue
    grep -q -- "--zz-bogus" <<<"$lout" || {
      fail "$c --$long: unexpected answer: $(head -2 <<<"$lout")"
      continue
    }
    taken=$((taken + 1))
    checks=$((checks + 1))
    # shellcheck disable=SC2086
    sout=$("$exe" $c "${sargs[@]}" --zz-bogus 2>&1)
    grep -q -- "unknown option '--zz-bogus'" <<<"$sout" ||
      fail "$c takes --$long but not -$short: $(head -2 <<<"$sout")"
    checks=$((checks + 1))
    # shellcheck disable=SC2086
    "$exe" $c --help | grep -Eq -- "(^| )-$short, --$long( |$)" ||
      fail "$c --help does not list '-$short, --$long'"
  done
done
# the pairs known today (a regression drops below this)
[ "$taken" -ge 16 ] || fail "only $taken command/option pairs found"

# ---- the short option is the long one ----
# its value reaches the same place: the messages name it
expect 2 "unknown scheme 'bogus'" "$exe" check -s bogus
expect 2 "unknown scheme 'bogus'" "$exe" jsr -s bogus --face
expect 2 "unknown scheme 'bogus'" "$exe" sweep -s bogus --edges 3..4 --db "$tmp/x.db"
expect 2 "unknown scheme 'bogus'" "$exe" analyze -s bogus --edge 4
expect 2 "--jobs '0' is not an integer" "$exe" check -s loop -j 0
expect 2 "--jobs '0' is not an integer" "$exe" sweep -s loop -j 0 --vertices 3..4
# and the same output
same() { # same NAME CMD1 -- CMD2: equal stdout and status
  local name=$1 a b ra rb
  shift
  local i=1
  while [ "${!i}" != "--" ]; do i=$((i + 1)); done
  local first=("${@:1:i-1}") second=("${@:i+1}")
  checks=$((checks + 1))
  a=$("${first[@]}" 2>/dev/null)
  ra=$?
  b=$("${second[@]}" 2>/dev/null)
  rb=$?
  if [ "$ra" -ne "$rb" ] || [ "$a" != "$b" ] || [ -z "$a" ]; then
    fail "$name: '${first[*]}' (status $ra) and '${second[*]}' (status $rb) differ"
  fi
}
same "analyze -s" "$exe" analyze -s loop --surface-vertex 5 -- \
  "$exe" analyze --scheme loop --surface-vertex 5
same "check -s -j" "$exe" check -s mlca --vertices 4..4 --edges 3..3 -j 2 -- \
  "$exe" check --scheme mlca --vertices 4..4 --edges 3..3 --jobs 2
"$exe" matrix -s loop --surface-vertex 4 -o "$tmp/m1.mtx" 2>/dev/null
"$exe" matrix --scheme loop --surface-vertex 4 --output "$tmp/m2.mtx" 2>/dev/null
checks=$((checks + 1))
[ -s "$tmp/m1.mtx" ] && cmp -s "$tmp/m1.mtx" "$tmp/m2.mtx" || fail "matrix -o / --output differ"

# ---- analyze -o FILE ----
for f in text json tsv; do
  "$exe" analyze -s catmull-clark --surface-vertex 5 --format $f -o "$tmp/a.$f" 2>/dev/null
  r1=$?
  "$exe" analyze -s catmull-clark --surface-vertex 5 --format $f >"$tmp/b.$f" 2>/dev/null
  r2=$?
  checks=$((checks + 1))
  [ "$r1" -eq "$r2" ] && [ -s "$tmp/a.$f" ] && cmp -s "$tmp/a.$f" "$tmp/b.$f" ||
    fail "analyze --format $f -o FILE differs from its standard output ($r1, $r2)"
done
expect 0 "^$" "$exe" analyze -s loop --surface-vertex 5 --output "$tmp/c.txt"
expect 0 "valence 5" cat "$tmp/c.txt"
# a stream of links: the results of all, in order, as on standard output
links=$'tetrahedron\noctahedron\n'
printf '%s' "$links" | "$exe" analyze -s mlca --vertex - --format tsv -o "$tmp/s.tsv" 2>/dev/null
printf '%s' "$links" | "$exe" analyze -s mlca --vertex - --format tsv >"$tmp/s2.tsv" 2>/dev/null
checks=$((checks + 1))
[ "$(wc -l <"$tmp/s.tsv")" -eq 3 ] && cmp -s "$tmp/s.tsv" "$tmp/s2.tsv" ||
  fail "analyze --vertex - -o FILE: $(wc -l <"$tmp/s.tsv") lines, or not as on stdout"
# bad input: exit 2 and the old file untouched (whole or not at all)
echo old >"$tmp/keep.txt"
expect_in 2 "stdin:2: " $'tetrahedron\nnot-a-link\n' "$exe" analyze -s mlca --vertex - -o "$tmp/keep.txt"
expect 0 "^old$" cat "$tmp/keep.txt"
expect 2 "nodir/x.txt" "$exe" analyze -s loop --surface-vertex 5 -o "$tmp/nodir/x.txt"

# ---- check --progress: the last line says all cases are done ----
expect 0 "subspectra check: \[[0-9.]+ s\] 4/4 cases done" "$exe" check -s mlca --vertices 4..5 --edges 3..4 --format json --progress -j 2
checks=$((checks + 1))
"$exe" check -s mlca --vertices 4..5 --edges 3..4 --format json 2>&1 >/dev/null | grep -q "cases done" &&
  fail "check without --progress printed progress"

# ---- sweep --progress / --quiet ----
# --progress: the progress header even though stderr is a pipe; without it none
expect 0 "^subspectra sweep: 3 cases of loop .* into .* with 1 thread" "$exe" sweep -s loop --vertices 3..5 --db "$tmp/p.db" -j 1 --progress
checks=$((checks + 1))
"$exe" sweep -s loop --vertices 3..6 --db "$tmp/q.db" -j 1 2>&1 | grep -q "cases of loop .* into .* with 1 thread" &&
  fail "sweep without --progress printed a progress line to a pipe"
expect 2 "--progress and --quiet: give one of them" "$exe" sweep -s loop --vertices 3..4 --progress -q
# on a terminal (script(1) gives it one): progress by default, none with -q
if command -v script >/dev/null; then
  checks=$((checks + 1))
  script -qec "'$exe' sweep -s loop --vertices 3..7 --db '$tmp/t1.db' -j 1" /dev/null >"$tmp/t1" 2>&1
  script -qec "'$exe' sweep -s loop --vertices 3..7 --db '$tmp/t2.db' -j 1 -q" /dev/null >"$tmp/t2" 2>&1
  grep -q "cases of loop .* into .* with 1 thread" "$tmp/t1" && ! grep -q "into .* with 1 thread" "$tmp/t2" &&
    grep -q "5 pass" "$tmp/t2" || fail "sweep on a terminal: -q does not silence the progress"
fi

# ---- --progress in jsr, limit and deform; silent without it ----
m=$src/data/meshes
expect 0 "^subspectra jsr: \[[0-9.]+ s\] branch and bound, word length 4" "$exe" jsr -s tetoct --edge 3 --depth 4 --progress
expect 0 "^subspectra limit: \[[0-9.]+ s\] points evaluated ([0-9]+)/\1$" "$exe" limit -s mlca "$m/hexstar-icosahedron.mesh" --samples 2 --progress
expect 0 "^subspectra deform: \[[0-9.]+ s\] writing" "$exe" deform -s mlca "$m/hexstar-icosahedron.mesh" --pattern grid --n 2 --target "$m/hexstar-icosahedron.mesh" --progress
for c in "jsr -s tetoct --edge 3 --depth 4" "limit -s mlca $m/hexstar-icosahedron.mesh --samples 2" \
  "deform -s mlca $m/hexstar-icosahedron.mesh --pattern grid --n 2 --target $m/hexstar-icosahedron.mesh"; do
  checks=$((checks + 1))
  # shellcheck disable=SC2086 # the command's words
  "$exe" $c 2>&1 >/dev/null | grep -q '\[[0-9.]* s\]' && fail "$c printed progress without --progress"
done

# ---- enumerate random: --seed only ----
expect 2 "enumerate random: -s is no longer the seed .*give --seed S" "$exe" enumerate random --vertices 8 --samples 1 -s 7
expect 0 "^8 bedch,ahfe,adgh,aefgc,abfd,bhgde,cdfh,acgfb$" "$exe" enumerate random --vertices 8 --samples 1 --seed 7

# ---- one JSON setting: '/' is not escaped ----
# limit's reason at the icosahedron vertex reads "... >= 1/2 and not 1/2"
# (json-c's default wrote 1\/2 there, as jsr did before)
expect 1 '>= 1/2 and not 1/2"' "$exe" limit -s mlca "$m/hexstar-icosahedron.mesh" --at "1 0 0 0" -d --format json
expect 0 '"threshold_name":"1/4' "$exe" jsr -s tetoct --face --depth 2 --max-seconds 1 --format json
checks=$((checks + 1))
calls=$(cat "$src"/cli/*.c | tr -d ' \n' | grep -o 'json_object_to_json_string_ext([^;]*;' )
[ -n "$calls" ] && ! grep -v 'SS_CLI_JSON_FLAGS)' <<<"$calls" | grep -q . ||
  fail "a command writes JSON with its own json-c flags: $(grep -v SS_CLI_JSON_FLAGS <<<"$calls" | head -2)"

# ---- messages: "subspectra COMMAND: ", nothing named twice ----
"$exe" sweep -s loop --vertices 3..4 --db "$tmp/m1.db" -j 1 2>"$tmp/sw.err" >/dev/null
expect 0 "^subspectra sweep: 2 cases of loop" cat "$tmp/sw.err"
expect 0 "^subspectra merge: .*m1.db: 2 results added" "$exe" merge "$tmp/m2.db" "$tmp/m1.db"
twice=0
while IFS= read -r c; do
  # shellcheck disable=SC2086 # the command's words
  while IFS= read -r line; do
    case $line in "subspectra "*) ;; "(see 'subspectra "*) continue ;; *)
      fail "$c: a message without the prefix: $line"
      continue
      ;;
    esac
    # the fields after the prefix: none may begin with the first two words
    # of an earlier one
    dup=$(awk -F': ' '{ for (i = 2; i <= NF; i++) { split($i, w, " "); k = w[1] " " w[2];
      if (w[2] != "" && k in seen) { print k; exit } seen[k] = 1 } }' <<<"$line")
    [ -n "$dup" ] && fail "$c: '$dup' twice in: $line" && twice=1
  done < <(cd "$tmp" && eval "\"$exe\" $c" 2>&1 >/dev/null)
  checks=$((checks + 1))
done <<EOF2
draw -s mlca --vertex octahedron -o x.jpg
draw -s mlca --edge 8 -o x.png
limit -s mlca $m/hexstar-icosahedron.mesh --at '1 0 0 0' -d
subdivide -s loop $m/cube-creased.mesh -o x.obj
subdivide -s mlca $src/tests/mesh/bad/index-out-of-range.mesh -o x.mesh
matrix -s mlca --edge 3 -o nodir/x.mtx
sweep -s mlca --vertices 4..5 --db nodir/x.db
merge m3.db nodir.db
report --db nodir.db
jsr -s mlca --face
enumerate mesh nodir.mesh
enumerate canonical < /dev/null --format xml
analyze -s mlca --vertex bad
EOF2

expect_done test_convention
