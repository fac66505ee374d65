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
. "$src/tests/sweep/ss_store_rows.sh"

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
expect 0 "2 cases .*2 computed.*0 already stored, 1 repeated link in --links skipped\): 2 pass" "$exe" sweep --scheme mlca --links "$tmp/links.txt" --db "$tmp/l.db"
expect 0 "^2\$" sqlite3 "$tmp/l.db" "SELECT count(*) FROM result"
# repeats of one link, and links that --vertices enumerates anyway, are run once
printf "octahedron\n6 cbfd,cefa,bade,cafe,cdfb,beda\nbipyramid:5\noctahedron\ntetrahedron\n" >"$tmp/links2.txt"
expect 0 "5 cases .*5 computed.*0 already stored, 4 repeated links in --links skipped\): 5 pass" \
  "$exe" sweep --scheme mlca --links "$tmp/links2.txt" --vertices 4..6 --db "$tmp/l2.db"
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

# hand-edited stores (issue 35): report, merge and sweep exit 2 naming the row,
# the column and the value (report read k = 'x' as 0, cells = -1 as 2^64 - 1,
# 'maybe' as undecided, results without their scheme as an empty store; merge
# of a kind outside the CHECK said "unknown error")
edit() { # edit NAME SQL: a copy of ref.db with SQL applied
  cp "$tmp/ref.db" "$tmp/$1.db"
  q "$tmp/$1.db" "$2" >/dev/null
}
edit k "UPDATE result SET k = 'x' WHERE scheme_id = 1 AND kind = 'edge' AND k = 5"
edit cells "UPDATE result SET cells = -1 WHERE scheme_id = 1 AND kind = 'edge' AND k = 5"
edit maybe "UPDATE result SET injectivity = 'maybe' WHERE scheme_id = 1 AND kind = 'edge' AND k = 5"
edit orphan "DELETE FROM scheme WHERE id = 1"
edit kind "PRAGMA ignore_check_constraints = 1; UPDATE result SET kind = 'vortex' WHERE scheme_id = 1 AND kind = 'edge' AND k = 5"
row="table result, row \\(scheme_id 1, kind 'edge', k"
for cmd in report merge sweep; do
  for f in k cells maybe orphan kind; do
    case $f in
    k) want="1 invalid row.*$row 'x', link ''\\): k = 'x' is not an integer" ;;
    cells) want="1 invalid row.*$row 5, link ''\\): cells = -1 is not an integer in 0\\.\\." ;;
    maybe) want="1 invalid row.*$row 5, .*injectivity = 'maybe' is not one of 'pass','fail','undecided'" ;;
    orphan) want="$(q "$tmp/ref.db" "SELECT count(*) FROM result WHERE scheme_id = 1") invalid rows.*scheme_id = 1 is not the id of a row of table scheme" ;;
    kind) want="1 invalid row.*kind = 'vortex' is not one of 'vertex','edge'" ;;
    esac
    case $cmd in
    report) expect 2 "$f.db: $want" "$exe" report --db "$tmp/$f.db" ;;
    merge) expect 2 "$f.db: $want" "$exe" merge "$tmp/m3.db" "$tmp/$f.db" ;;
    sweep) expect 2 "$f.db: $want" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/$f.db" ;;
    esac
  done
done
expect 0 "^0\$" sqlite3 "$tmp/m3.db" "SELECT count(*) FROM result"

# merge conflicts: the same case with other values is reported, OUT's row
# kept, exit 1, the other rows merged; --prefer old keeps, --prefer new
# replaces; a different timing alone is no conflict
cp "$tmp/p1.db" "$tmp/c_in.db"
cp "$tmp/p1.db" "$tmp/c_out.db"
q "$tmp/c_out.db" "DELETE FROM result WHERE kind = 'vertex' AND k = 9" # rows to add
q "$tmp/c_in.db" "UPDATE result SET seconds = seconds + 1"
q "$tmp/c_in.db" "UPDATE result SET min_scaled_jacobian = min_scaled_jacobian * 2 WHERE kind = 'edge'"
nconf=$(q "$tmp/c_in.db" "SELECT count(*) FROM result WHERE kind = 'edge'")
nadd=$(q "$tmp/p1.db" "SELECT count(*) FROM result WHERE kind = 'vertex' AND k = 9")
firstk=$(q "$tmp/c_in.db" "SELECT min(k) FROM result WHERE kind = 'edge'")
checks=$((checks + 1))
[ "$nconf" -ge 1 ] && [ "$nadd" -ge 1 ] || fail "conflict setup: $nconf edge rows, $nadd k = 9 rows in part 1"
old_edges=$(rows "$tmp/c_out.db" | grep '|edge|')
expect 1 "c_in.db: $nadd results added, [0-9]+ already in .*c_out.db\$" \
  "$exe" merge "$tmp/c_out.db" "$tmp/c_in.db"
# (again: the conflicts stay, and are the second line)
expect 1 "c_in.db: $nconf conflicts? with .*c_out.db \(the same case with other values; first: \(mlca tol=1e-06 depth=6 rings=3\) edge $firstk[;)].*--prefer new" \
  "$exe" merge "$tmp/c_out.db" "$tmp/c_in.db"
checks=$((checks + 1))
[ "$(rows "$tmp/c_out.db" | grep '|edge|')" = "$old_edges" ] || fail "merge without --prefer changed a conflicting row"
expect 0 "^$(q "$tmp/p1.db" "SELECT count(*) FROM result")\$" sqlite3 "$tmp/c_out.db" "SELECT count(*) FROM result"
expect 0 "0 results added.*$nconf conflicting results kept" "$exe" merge --prefer old "$tmp/c_out.db" "$tmp/c_in.db"
checks=$((checks + 1))
[ "$(rows "$tmp/c_out.db" | grep '|edge|')" = "$old_edges" ] || fail "--prefer old changed a conflicting row"
expect 0 "$nconf conflicting results replaced" "$exe" merge "$tmp/c_out.db" "$tmp/c_in.db" --prefer new
same "--prefer new takes the input's rows" "$tmp/c_in.db" "$tmp/c_out.db"
expect 0 "0 results added, [0-9]+ already in" "$exe" merge "$tmp/c_out.db" "$tmp/c_in.db"
expect 2 "--prefer: expected new or old" "$exe" merge --prefer newest "$tmp/c_out.db" "$tmp/c_in.db"
# a store merged into itself, by the same or another name: said so at once
ln -s c_out.db "$tmp/c_link.db"
expect 2 "c_out.db is the output store .*c_out.db itself" "$exe" merge "$tmp/c_out.db" "$tmp/c_out.db"
expect 2 "c_link.db is the output store .*c_out.db itself" "$exe" merge "$tmp/c_out.db" "$tmp/c_link.db"
expect 2 "/\./c_out.db is the output store" "$exe" merge "$tmp/c_link.db" "$tmp/./c_out.db"

# tolerances are exact in the identity: 1.0000006e-6 is not 1e-6
expect 0 "1 cases of mlca tol=1e-06 depth=6 .*1 computed" "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/tol.db"
expect 0 "1 cases of mlca tol=1.0000006e-06 depth=6 .*1 computed" "$exe" sweep --scheme mlca --edges 3..3 --tol 1.0000006e-6 --db "$tmp/tol.db"
expect 0 "^2\$" sqlite3 "$tmp/tol.db" "SELECT count(*) FROM result"
# a store of an older program: a scheme row whose identity rounded its
# tolerance is not reused for another tolerance of that text
q "$tmp/tol.db" "UPDATE scheme SET tol = 1.0000006e-6 WHERE identity LIKE '% tol=1e-06 %'"
expect 2 "tol.db: scheme 'mlca tol=1e-06 depth=6 rings=3' was stored by an older subspectra for the tolerance 1.0000006" \
  "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/tol.db"

# a store another program holds locked: said so (after a few seconds).  The
# locker waits for the probe's read lock (.timeout): without it, BEGIN
# EXCLUSIVE racing a probe failed with "database is locked" and the sqlite3
# program went on to sleep holding nothing (seen once under load)
cp "$tmp/p1.db" "$tmp/lock.db"
sqlite3 "$tmp/lock.db" ".timeout 10000" "PRAGMA locking_mode=EXCLUSIVE;" "BEGIN EXCLUSIVE;" \
  "INSERT INTO meta VALUES('lock','held');" ".shell sleep 20" "ROLLBACK;" >/dev/null 2>&1 &
lockpid=$!
locked=0
for _ in $(seq 1 200); do
  sqlite3 "$tmp/lock.db" "SELECT count(*) FROM meta" >/dev/null 2>&1 || { locked=1; break; }
  sleep 0.05
done
checks=$((checks + 1))
[ "$locked" = 1 ] || fail "could not lock lock.db with the sqlite3 program"
expect 2 "lock.db: the results store is locked by another process" \
  "$exe" sweep --scheme mlca --edges 3..3 --db "$tmp/lock.db"
kill "$lockpid" 2>/dev/null
wait "$lockpid" 2>/dev/null

# SIGTERM while the cases are counted (before the first is computed): said
# so, the store left sound, death by the signal
db=$tmp/count.db
"$exe" sweep --scheme mlca --vertices 4..16 --db "$db" >/dev/null 2>"$tmp/count.err" &
pid=$!
for _ in $(seq 1 600); do
  [ "$(sqlite3 "$db" "SELECT count(*) FROM scheme" 2>/dev/null)" = 1 ] && break
  sleep 0.02
done
sleep 0.3
kill -TERM "$pid"
wait "$pid"
rc=$?
checks=$((checks + 1))
[ "$rc" = 143 ] && grep -q "interrupted (SIGTERM) while counting the cases" "$tmp/count.err" ||
  fail "SIGTERM while counting: status $rc, $(cat "$tmp/count.err")"
expect 0 "^ok\$" sqlite3 "$db" "PRAGMA integrity_check"
expect 0 "^0\$" sqlite3 "$db" "SELECT count(*) FROM result"

# processes sharing a store may all create it at once: one creates the
# schema, the others use it (three rounds of four)
bad=0
for r in 1 2 3; do
  pids=""
  for i in 1 2 3 4; do
    "$exe" sweep --scheme mlca --edges 3..3 --jobs 1 --db "$tmp/new$r.db" >"$tmp/new$r.$i.out" 2>&1 &
    pids="$pids $!"
  done
  for p in $pids; do wait "$p" || bad=$((bad + 1)); done
done
checks=$((checks + 1))
[ "$bad" = 0 ] || fail "$bad of 12 sweeps creating one store at once failed: $(grep -hv '^subspectra sweep: 1 cases' "$tmp"/new*.out | head -2)"
expect 0 "^1\$" sqlite3 "$tmp/new3.db" "SELECT count(*) FROM result"

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
[ "$(wc -l <<<"$err")" = 1 ] && grep -q "^subspectra sweep: 23 cases" <<<"$err" ||
  fail "non-terminal stderr should carry one summary line, got: $err"
# (script is util-linux's, essential on Debian: always run, never skipped)
checks=$((checks + 1))
command -v script >/dev/null || fail "script (util-linux) not installed: the terminal progress check cannot run"
tty=$(script -qec "$exe sweep --scheme mlca --vertices 4..9 --db $tmp/pt.db" /dev/null)
grep -q "cases/s, ETA " <<<"$tty" && grep -q "sweep: 73 cases of mlca" <<<"$tty" ||
  fail "no progress line on a terminal: $(tail -c 300 <<<"$tty")"
# a certified sweep's progress counts the computed cases it proved: never
# more than computed, some, and at most the proven rows of the store
checks=$((checks + 1))
tty=$(script -qec "$exe sweep --scheme tetoct --vertices 4..10 --certify --jobs 1 --db $tmp/pc.db" /dev/null |
  tr '\r' '\n' | grep -o "[0-9]* of [0-9]* computed proven")
stored=$(q "$tmp/pc.db" "SELECT count(*) FROM cases WHERE
  (verdict = 'pass' AND eigen_certified AND regularity_certified) OR (verdict = 'fail' AND
  ((eigen_condition = 'fail' AND eigen_certified) OR (regularity = 'fail' AND regularity_certified)
   OR (injectivity = 'fail' AND injectivity_certified)))")
bad=$(awk -v s="$stored" '$1 > $3 || $1 > s' <<<"$tty")
last=$(tail -1 <<<"$tty")
[ -n "$tty" ] && [ -z "$bad" ] && [ "${last%% *}" -gt 0 ] ||
  fail "certified progress: '$last' (store: $stored proven), inconsistent: '$bad'"

expect_done test_sweep
