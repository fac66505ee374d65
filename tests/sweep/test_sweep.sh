#!/usr/bin/env bash
# test_sweep.sh EXE SRCDIR — `subspectra sweep` and `merge` from the outside:
# a sweep killed with SIGKILL at three moments and resumed stores exactly the
# rows of an uninterrupted sweep, no duplicates; 2 threads store what 1 thread
# stores; parts merged equal the whole; stored verdicts count on resume;
# corrupt, foreign and truncated stores exit 2; progress only on a terminal.
set -u
exe=$1
src=$2
SS_EXPECT_TIMEOUT=240
. "$src/tests/ss_expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

command -v sqlite3 >/dev/null || { echo "test_sweep: sqlite3 not installed (./run installs it)"; exit 1; }
q() { sqlite3 "$@"; }  # (expect runs programs: call sqlite3 there)
# every column that a result's mathematics determines (not the timing)
rows() {
  q "$1" "SELECT s.identity, kind, k, link, cells, two_ring, one_ring, eigenvalues,
          eigen_condition, eigen_reason, tolerance, regularity, regularity_reason,
          quote(min_scaled_jacobian), r.depth, quote(improper_pairs), quote(adjacent_pairs),
          quote(lambda1), quote(lambda4)
          FROM result r JOIN scheme s ON s.id = r.scheme_id ORDER BY 1, 2, 3, 4"
}
same() { # same NAME DB1 DB2: equal rows, and not vacuously
  checks=$((checks + 1))
  local a b
  a=$(rows "$2")
  b=$(rows "$3")
  [ -n "$a" ] && [ "$a" = "$b" ] || fail "$1: stores differ ($(diff <(echo "$a") <(echo "$b") | head -3))"
}

# the reference: all 306 links with 4..10 vertices and edges 3..8, one thread
expect 1 "312 cases of mlca tol=1e-06 depth=6 rings=3 .*312 computed.*1 thread.*0 already stored" \
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$tmp/ref.db" --jobs 1
total=$(q "$tmp/ref.db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ "$total" = 312 ] || fail "reference sweep stored $total rows, want 312 (306 links + 6 edges)"

# threads: 2 threads store exactly what 1 thread stores
expect 1 "312 computed.*2 threads" "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 \
  --db "$tmp/two.db" --jobs 2
same "2 threads vs 1 thread" "$tmp/ref.db" "$tmp/two.db"

# SIGKILL at three moments, then resume
db=$tmp/kill.db
midway=0
for target in 40 130 220; do
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$db" --jobs 2 2>/dev/null &
  pid=$!
  n=0
  for _ in $(seq 1 600); do
    kill -0 "$pid" 2>/dev/null || break
    n=$(q "$db" "SELECT count(*) FROM result" 2>/dev/null || echo 0)
    [ "${n:-0}" -ge "$target" ] && break
    sleep 0.02
  done
  kill -KILL "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  n=$(q "$db" "SELECT count(*) FROM result")
  [ "$n" -gt 0 ] && [ "$n" -lt "$total" ] && midway=$((midway + 1))
done
checks=$((checks + 1))
[ "$midway" -ge 1 ] || fail "no kill landed in the middle of the sweep (machine too fast?)"
before=$(q "$db" "SELECT count(*) FROM result")
expect 1 "312 cases .*\($((total - before)) computed.*; $before already stored\)" \
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$db" --jobs 2
expect 0 "^$total\$" sqlite3 "$db" "SELECT count(*) FROM result"
expect 0 "^$total\$" sqlite3 "$db" "SELECT count(*) FROM (SELECT DISTINCT scheme_id, kind, k, link FROM result)"
same "killed three times and resumed vs uninterrupted" "$tmp/ref.db" "$db"
expect 0 "^ok\$" sqlite3 "$db" "PRAGMA integrity_check"

# the verdict counts a summary must report, recounted from the reference
# store's rows (not pasted from a run's output)
npass=$(q "$tmp/ref.db" "SELECT count(*) FROM cases WHERE verdict = 'pass'")
nfail=$(q "$tmp/ref.db" "SELECT count(*) FROM cases WHERE verdict = 'fail'")
nund=$(q "$tmp/ref.db" "SELECT count(*) FROM cases WHERE verdict = 'undecided'")
checks=$((checks + 1))
[ $((npass + nfail + nund)) = "$total" ] && [ "$nfail" -gt 0 ] ||
  fail "reference verdicts: $npass pass, $nfail fail, $nund undecided of $total"

# SIGINT: the cases in flight are finished and stored, the summary says how
# far it got, the process dies of the signal; --format json on stdout
db=$tmp/int.db
"$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$db" --format json >"$tmp/int.json" 2>"$tmp/int.err" &
pid=$!
for _ in $(seq 1 600); do
  n=$(sqlite3 "$db" "SELECT count(*) FROM result" 2>/dev/null || echo 0)
  [ "${n:-0}" -ge 60 ] && break
  sleep 0.02
done
kill -INT "$pid"
wait "$pid"
rc=$?
n=$(sqlite3 "$db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ "$rc" = 130 ] && grep -q "interrupted (SIGINT) with $n of 312 cases done; the same command resumes" "$tmp/int.err" &&
  grep -q "\"cases\":312,\"done\":$n,\"computed\":$n,.*\"interrupted\":true" "$tmp/int.json" ||
  fail "SIGINT: status $rc, $n rows; $(cat "$tmp/int.err" "$tmp/int.json")"
expect 1 "\"computed\":$((total - n)),\"already_stored\":$n,\"pass\":$npass,\"fail\":$nfail,.*\"interrupted\":false" \
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$db" --format json
same "interrupted by SIGINT and resumed vs uninterrupted" "$tmp/ref.db" "$db"

# a finished sweep rerun computes nothing and still reports the stored verdicts
expect 1 "0 computed.*312 already stored\): $npass pass, $nfail fail" \
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$db"
expect 0 "0 computed.*2 already stored\): 2 pass, 0 fail" \
  "$exe" sweep --scheme mlca --vertices 4..5 --db "$db"

# parts: three parts in three stores, merged, are the whole; merging twice adds nothing
for i in 0 1 2; do
  "$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --part $i/3 --db "$tmp/p$i.db" 2>/dev/null
done
p0=$(q "$tmp/p0.db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ "$p0" -gt 0 ] && [ "$p0" -lt "$total" ] || fail "part 0/3 has $p0 rows of $total"
expect 0 "p2.db: [0-9]+ results added, 0 already" "$exe" merge "$tmp/merged.db" "$tmp/p0.db" "$tmp/p1.db" "$tmp/p2.db"
same "parts merged vs whole" "$tmp/ref.db" "$tmp/merged.db"
expect 0 "p1.db: 0 results added, [0-9]+ already in" "$exe" merge "$tmp/merged.db" "$tmp/p1.db"
expect 0 "^$total\$" sqlite3 "$tmp/merged.db" "SELECT count(*) FROM result"

# scheme identity: the MLCA stencil file is another identity with the same numbers
expect 0 "stencil:[0-9a-f]{16} tol=1e-06 depth=6 rings=3" "$exe" sweep --stencil "$src/data/stencils/mlca.ini" \
  --vertices 4..7 --edges 3..5 --db "$tmp/ref.db"
expect 0 "^2\$" sqlite3 "$tmp/ref.db" "SELECT count(*) FROM scheme"
checks=$((checks + 1))
a=$(q "$tmp/ref.db" "SELECT kind,k,link,eigenvalues,regularity,min_scaled_jacobian FROM result r JOIN scheme s ON s.id=r.scheme_id WHERE s.identity LIKE 'stencil:%' ORDER BY 1,2,3")
b=$(q "$tmp/ref.db" "SELECT kind,k,link,eigenvalues,regularity,min_scaled_jacobian FROM result r JOIN scheme s ON s.id=r.scheme_id WHERE s.identity LIKE 'mlca %' AND (kind IN ('vertex','edge-point') AND k<=7 OR kind='edge' AND k<=5) ORDER BY 1,2,3")
[ -n "$a" ] && [ "$a" = "$b" ] || fail "stencil mlca.ini and scheme mlca store different results"
# other analysis parameters are other identities
expect 0 "mlca tol=0.0001 depth=6 rings=3" "$exe" sweep --scheme mlca --edges 3..4 --tol 1e-4 --db "$tmp/ref.db"
expect 0 "boxspline tol=1e-06 depth=6 rings=3 diagonals=skew" "$exe" sweep --scheme boxspline --edges 4..5 --diagonals skew --db "$tmp/ref.db"
# --certify is another identity; its verdicts are proven (MLCA edges 3..5)
expect 0 "mlca tol=1e-06 depth=6 rings=3 certified" "$exe" sweep --scheme mlca --edges 3..5 --certify --db "$tmp/ref.db"
expect 0 "^3\$" sqlite3 "$tmp/ref.db" "SELECT count(*) FROM result r JOIN scheme s ON s.id = r.scheme_id WHERE s.certify = 1 AND r.eigen_certified = 1 AND r.regularity_certified = 1 AND r.regularity = 'pass'"
# and report counts them (valence 4: 1 case, 1 pass, 1 certified)
expect 0 "^mlca tol=1e-06 depth=6 rings=3 certified,mlca,edge,4,1,1,0,0,0,[^,]*,[^,]*,[^,]*,1" "$exe" report --db "$tmp/ref.db" --table summary --format csv --where "identity LIKE '%certified%'"

# --links: isomorphic links (relabelled, mirrored) are one case; bad lines exit 2
printf '# three names of two links\noctahedron\n6 bcde,aedf,abfe,afeb... \n' >"$tmp/bad.txt"
expect 2 "bad.txt:3: " "$exe" sweep --scheme mlca --links "$tmp/bad.txt" --db "$tmp/l.db"
printf "octahedron\n6 cbfd,cefa,bade,cafe,cdfb,beda\nbipyramid:3\n" >"$tmp/links.txt"
expect 0 "3 cases .*2 computed.*1 already stored\): 3 pass" "$exe" sweep --scheme mlca --links "$tmp/links.txt" --db "$tmp/l.db"
expect 0 "^2\$" sqlite3 "$tmp/l.db" "SELECT count(*) FROM result"
expect_in 0 "1 cases .*0 computed.*1 already stored" "octahedron
" "$exe" sweep --scheme mlca --links - --db "$tmp/l.db"
expect 0 "^2\$" sqlite3 "$tmp/l.db" "SELECT count(*) FROM result"
# surface schemes: --vertices are vertex valences
expect 0 "4 cases of catmull-clark .*4 pass" "$exe" sweep --scheme catmull-clark --vertices 3..6 --db "$tmp/l.db"
expect 0 "^4\$" sqlite3 "$tmp/l.db" "SELECT count(*) FROM result WHERE kind = 'surface-vertex'"

# bad stores exit 2 and are left alone
head -c 3000 /dev/urandom >"$tmp/noise.db"
expect 2 "noise.db: not a subspectra results store" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/noise.db"
q "$tmp/foreign.db" "CREATE TABLE t(x); INSERT INTO t VALUES(1);"
expect 2 "foreign.db: a foreign SQLite database" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/foreign.db"
expect 0 "^1\$" sqlite3 "$tmp/foreign.db" "SELECT count(*) FROM t"
cp "$tmp/two.db" "$tmp/v99.db"
q "$tmp/v99.db" "PRAGMA user_version = 99"
expect 2 "v99.db: results store of schema version 99" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/v99.db"
q "$tmp/two.db" "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
size=$(stat -c %s "$tmp/two.db")
head -c $((size / 2)) "$tmp/two.db" >"$tmp/cut.db"
expect 2 "cut.db: (corrupt results store|not a subspectra results store)" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/cut.db"
expect 2 "noise.db: not a subspectra results store" "$exe" merge "$tmp/m2.db" "$tmp/noise.db"
expect 2 "foreign.db: a foreign SQLite database" "$exe" merge "$tmp/m2.db" "$tmp/foreign.db"
expect 2 "nothere.db: no such results store" "$exe" merge "$tmp/m2.db" "$tmp/nothere.db"

# a store in a directory the reader may not write (WAL wants a -shm file
# beside it) is still read; needs root to play another user, else skipped
if [ "$(id -u)" = 0 ] && command -v su >/dev/null &&
  su nobody -s /bin/sh -c "'$exe' --version" >/dev/null 2>&1; then
  ro=$(mktemp -d /tmp/ss_ro.XXXXXX)
  sqlite3 "$tmp/merged.db" "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
  cp "$tmp/merged.db" "$ro/s.db"
  chmod 644 "$ro/s.db"
  chmod 555 "$ro"
  checks=$((checks + 1))
  # (233 links with 10 vertices: 232 vertices and the bipyramid over 8, an edge point)
  out=$(su nobody -s /bin/sh -c "'$exe' report --db '$ro/s.db' --format csv --table summary" 2>&1)
  grep -q "^mlca tol=1e-06 depth=6 rings=3,mlca,vertex,10,232," <<<"$out" ||
    fail "read-only directory: $(head -3 <<<"$out")"
  [ -z "$(ls "$ro" | grep -v '^s.db$')" ] || fail "files left beside a read-only store: $(ls "$ro")"
  chmod 755 "$ro"
  rm -rf "$ro"
fi

# usage errors
expect 2 "no cases" "$exe" sweep --scheme mlca --db "$tmp/u.db"
expect 2 "exactly one of --scheme and --stencil" "$exe" sweep --edges 3..4 --db "$tmp/u.db"
expect 2 "--jobs '0'" "$exe" sweep --scheme mlca --edges 3..4 --jobs 0 --db "$tmp/u.db"
expect 2 "--part '3/3'" "$exe" sweep --scheme mlca --edges 3..4 --part 3/3 --db "$tmp/u.db"
expect 2 "links have 4..20 vertices" "$exe" sweep --scheme mlca --vertices 3..5 --db "$tmp/u.db"
expect 2 "--face: the scheme does not split tets" "$exe" sweep --scheme mlca --face --db "$tmp/u.db"
expect 2 "--diagonals: the scheme reads no major diagonals" "$exe" sweep --scheme mlca --edges 3..4 --diagonals proper --db "$tmp/u.db"
expect 2 "--edges only" "$exe" sweep --scheme boxspline --vertices 5..5 --diagonals skew --db "$tmp/u.db"
expect 2 "unknown scheme" "$exe" sweep --scheme nope --edges 3..4 --db "$tmp/u.db"
expect 0 "resumes where it stopped" "$exe" sweep --help
expect 0 "usage: subspectra merge" "$exe" merge --help
expect 2 "need OUT.db" "$exe" merge "$tmp/u.db"

# progress: none when stderr is not a terminal (only the summary line), a
# live line with rate and ETA on a terminal
checks=$((checks + 1))
err=$("$exe" sweep --scheme mlca --vertices 4..8 --db "$tmp/pr.db" 2>&1 >/dev/null)
[ "$(wc -l <<<"$err")" = 1 ] && grep -q "^sweep: 23 cases" <<<"$err" ||
  fail "non-terminal stderr should carry one summary line, got: $err"
if command -v script >/dev/null; then
  checks=$((checks + 1))
  tty=$(script -qec "$exe sweep --scheme mlca --vertices 4..9 --db $tmp/pt.db" /dev/null)
  grep -q "cases/s, ETA " <<<"$tty" && grep -q "sweep: 73 cases of mlca" <<<"$tty" ||
    fail "no progress line on a terminal: $(tail -c 300 <<<"$tty")"
fi

expect_done test_sweep
