#!/usr/bin/env bash
# test_enumerate_cli.sh EXE — `subspectra enumerate links` and `enumerate
# canonical` from the outside: counts, parts, canonical forms of relabelled and
# mirrored links, and exit status 2 with a message naming the line for every
# malformed link.
set -u
exe=$1
. "$(dirname "$0")/../ss_expect.sh"

expect_in 0 "Every link" "" "$exe" enumerate links --help
expect_in 0 "canonical form" "" "$exe" enumerate canonical --help
expect_in 0 "links" "" "$exe" enumerate --help
expect_in 2 "--vertices is required" "" "$exe" enumerate links
expect_in 2 "--vertices '3'" "" "$exe" enumerate links --vertices 3
expect_in 2 "--vertices '9..8'" "" "$exe" enumerate links --vertices 9..8
expect_in 2 "--vertices '21'" "" "$exe" enumerate links --vertices 21
expect_in 2 "--part '3/3'" "" "$exe" enumerate links --vertices 8 --part 3/3
expect_in 2 "--part 'x'" "" "$exe" enumerate links --vertices 8 --part x
expect_in 2 "unknown option '--bogus'" "" "$exe" enumerate links --bogus
expect_in 2 "unknown 'enumerate frob'" "" "$exe" enumerate frob
expect_in 2 "no links read" "" "$exe" enumerate canonical

# counts, as a table and as JSON
checks=$((checks + 1))
got=$("$exe" enumerate links --vertices 4..11 --count 2>/dev/null | grep -v '^#' | cut -f2 | tr '\n' ' ')
[ "$got" = "1 1 2 5 14 50 233 1249 " ] || fail "counts 4..11: $got"
# k = 12 and 14 hold the first links of minimum degree 5 (the icosahedron and
# one more), the only ones made by E5: the published counts to 14 (< 1 s)
checks=$((checks + 1))
got=$("$exe" enumerate links --vertices 12..14 --count 2>/dev/null | grep -v '^#' | cut -f2 | tr '\n' ' ')
[ "$got" = "7595 49566 339722 " ] || fail "counts 12..14: $got"
checks=$((checks + 1))
"$exe" enumerate links --vertices 10 --count --format json 2>/dev/null |
  python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["counts"]["10"]==233, d' ||
  fail "json count"

# every listed link canonicalizes to a distinct form; parts partition the set
checks=$((checks + 1))
n=$("$exe" enumerate links --vertices 9 2>/dev/null | "$exe" enumerate canonical | sort -u | wc -l)
[ "$n" -eq 50 ] || fail "k = 9: $n distinct canonical forms, expected 50"
checks=$((checks + 1))
all=$(for i in 0 1 2 3 4; do "$exe" enumerate links --vertices 10 --part $i/5 2>/dev/null; done |
  "$exe" enumerate canonical)
[ "$(wc -l <<<"$all")" -eq 233 ] && [ "$(sort -u <<<"$all" | wc -l)" -eq 233 ] ||
  fail "parts of k = 10: $(wc -l <<<"$all") lines, $(sort -u <<<"$all" | wc -l) distinct"

# relabelled, rotated and mirrored inputs give one canonical form; names work
# scramble: relabel a plantri link randomly, turn each list, optionally mirror
scramble() {
  python3 -c '
import random, sys
random.seed(int(sys.argv[2])); mirror = sys.argv[3] == "1"
k, lists = sys.argv[1].split(" ", 1)
lists = [[ord(c) - 97 for c in x] for x in lists.split(",")]
n = len(lists); perm = list(range(n)); random.shuffle(perm)
out = [None] * n
for v, l in enumerate(lists):
    l = [perm[w] for w in l]
    r = random.randrange(len(l)); l = l[r:] + l[:r]
    out[perm[v]] = l[::-1] if mirror else l
print(k, ",".join("".join(chr(97 + w) for w in l) for l in out))' "$@"
}
checks=$((checks + 1))
oct=$("$exe" enumerate canonical <<<"octahedron")
forms=$(printf '%s\n' "$(scramble "$oct" 1 0)" "octahedron" "bipyramid:4" "$(scramble "$oct" 2 1)" |
  "$exe" enumerate canonical | sort -u | wc -l)
[ "$forms" -eq 1 ] || fail "octahedron in four guises: $forms canonical forms"
checks=$((checks + 1))
forms=$("$exe" enumerate links --vertices 9 2>/dev/null | while read -r l; do
  scramble "$l" 3 1
done | "$exe" enumerate canonical | sort -u | wc -l)
[ "$forms" -eq 50 ] || fail "mirrored relabelled k = 9 links: $forms canonical forms, expected 50"
checks=$((checks + 1))
forms=$(printf '%s\n' "bipyramid:5" "icosahedron" "bipyramid:10" | "$exe" enumerate canonical | sort -u | wc -l)
[ "$forms" -eq 3 ] || fail "distinct links: $forms canonical forms, expected 3"
expect_in 0 '"automorphisms":120' "icosahedron" "$exe" enumerate canonical --format json

# malformed links: status 2, the line number and the problem
ok="4 bcd,adc,abd,acb"
expect_in 2 "stdin:2: the vertex count is 5 but there are 4" "$ok
5 bcd,adc,abd,acb
" "$exe" enumerate canonical
expect_in 2 "stdin:4: .*not symmetric" "$ok
# a comment line

5 bcde,adc,abd,acb,bcd
" "$exe" enumerate canonical
# the 3x3 triangulated torus: consistent rotations, Euler characteristic 0
torus=$(python3 -c '
d = [(1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1)]
print(9, ",".join("".join(chr(97 + ((i + a) % 3) * 3 + (j + b) % 3) for a, b in d)
                  for i in range(3) for j in range(3)))')
expect_in 2 "stdin:1: .*not a sphere" "$torus" "$exe" enumerate canonical
expect_in 2 "stdin:1: .*multi-edge" "4 bbd,adc,abd,acb" "$exe" enumerate canonical
expect_in 2 "stdin:1: .*degree 2" "5 bcd,acd,abd,abc,ab" "$exe" enumerate canonical
expect_in 2 "stdin:1: .*rotations do not form triangles" "4 bcd,acd,abd,acb" "$exe" enumerate canonical
expect_in 2 "stdin:1: .*unknown link 'cube'" "cube" "$exe" enumerate canonical

expect_done "enumerate cli"
