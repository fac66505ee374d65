#!/usr/bin/env bash
# test_sweep_root.sh EXE SRCDIR — the store checks that need root: a store in a
# directory (or on a file system) the reader may not write is still read by
# report and merge, and sweep says why it cannot write there.  Without root,
# su or unshare -m the test is reported as skipped (exit 77) with the reason.
set -u
exe=$1
src=$2
SS_EXPECT_TIMEOUT=240
. "$src/tests/ss_expect.sh"
. "$src/tests/sweep/ss_store_rows.sh"
command -v sqlite3 >/dev/null || { echo "test_sweep_root: sqlite3 not installed (./run installs it)"; exit 1; }
if [ "$(id -u)" != 0 ]; then
  echo "test_sweep_root: SKIPPED — needs root (to play user nobody and to mount read-only)"
  exit 77
fi
if ! command -v su >/dev/null || ! su nobody -s /bin/sh -c "'$exe' --version" >/dev/null 2>&1; then
  echo "test_sweep_root: SKIPPED — user nobody cannot run $exe (su missing, or the build tree is not readable by others)"
  exit 77
fi
probe=$(mktemp -d /tmp/ss_probe.XXXXXX)
roenv=(unshare -m sh -c 'd=$1; shift; mount --bind "$d" "$d" && mount -o remount,ro,bind "$d" && exec "$@"' sh)
if ! command -v unshare >/dev/null || ! "${roenv[@]}" "$probe" sh -c "! touch '$probe/x'" 2>/dev/null; then
  rm -rf "$probe"
  echo "test_sweep_root: SKIPPED — cannot make a read-only bind mount (unshare -m; in a container without CAP_SYS_ADMIN?)"
  exit 77
fi
rm -rf "$probe"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# the store read below (every MLCA link k <= 10 and edges 3..8), computed once
"$exe" sweep --scheme mlca --vertices 4..10 --edges 3..8 --db "$tmp/merged.db" 2>/dev/null
sqlite3 "$tmp/merged.db" "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
cp "$tmp/merged.db" "$tmp/p1.db"
checks=$((checks + 1))
[ "$(q "$tmp/merged.db" "SELECT count(*) FROM result")" = 312 ] || fail "setup: the k <= 10 store has not 312 rows"

# a store in a directory the reader may not write (WAL wants a -shm file
# beside it) is still read, as another user
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

# stores on a read-only file system (a read-only bind mount in a mount
# namespace of our own: needs root and unshare): merge reads them, sweep says
# why it cannot write them
rodir=$(mktemp -d /tmp/ss_rofs.XXXXXX)
sqlite3 "$tmp/p1.db" "PRAGMA wal_checkpoint(TRUNCATE)" >/dev/null
cp "$tmp/p1.db" "$rodir/s.db"
roenv+=("$rodir")
expect 0 "s.db: [0-9]+ results added, 0 already in" "${roenv[@]}" "$exe" merge "$tmp/rofs_out.db" "$rodir/s.db"
same "merged from a read-only file system" "$tmp/p1.db" "$tmp/rofs_out.db"
expect 2 "s.db: cannot write the results store: a read-only file system" \
  "${roenv[@]}" "$exe" sweep --scheme mlca --edges 3..3 --db "$rodir/s.db"
expect 2 "new.db: cannot create the results store: directory .*: a read-only file system" \
  "${roenv[@]}" "$exe" sweep --scheme mlca --edges 3..3 --db "$rodir/new.db"
checks=$((checks + 1))
[ "$(ls "$rodir")" = s.db ] || fail "files left on the read-only file system: $(ls "$rodir")"
rm -rf "$rodir"
# the same by permissions, as a user who may not write (needs root to be nobody)
ro=$(mktemp -d /tmp/ss_ro.XXXXXX)
wr=$(mktemp -d /tmp/ss_wr.XXXXXX)
cp "$tmp/p1.db" "$ro/s.db"
chmod 644 "$ro/s.db"
chmod 555 "$ro"
chmod 777 "$wr"
checks=$((checks + 1))
out=$(su nobody -s /bin/sh -c "'$exe' merge '$wr/o.db' '$ro/s.db'" 2>&1) ||
  fail "merge from a directory the user may not write: $out"
same "merged from a read-only directory" "$tmp/p1.db" "$wr/o.db"
checks=$((checks + 1))
out=$(su nobody -s /bin/sh -c "'$exe' sweep --scheme mlca --edges 3..3 --db '$ro/s.db'" 2>&1)
[ $? = 2 ] && grep -q "s.db: cannot write the results store: no write permission on the file" <<<"$out" ||
  fail "sweep into a store the user may not write: $out"
checks=$((checks + 1))
out=$(su nobody -s /bin/sh -c "'$exe' sweep --scheme mlca --edges 3..3 --db '$ro/new.db'" 2>&1)
[ $? = 2 ] && grep -q "new.db: cannot create the results store: directory .*: no write permission" <<<"$out" ||
  fail "sweep into a directory the user may not write: $out"
chmod 755 "$ro"
rm -rf "$ro" "$wr"

expect_done test_sweep_root
