#!/usr/bin/env bash
# test_sweep_mpi.sh EXE SRCDIR MPI — `subspectra sweep` as one MPI job: with
# `mpirun --oversubscribe -n 3` (rank 0 hands out the cases and writes the
# store, two ranks compute) the store equals the single-process store row
# for row; `mpirun -n 1` is the threaded sweep; a computing rank killed with
# SIGKILL mid-run leaves a sound partial store that the same command
# completes, computing only what is missing; a stopped rank holds only its
# piece (dynamic distribution), a rank ended alone by SIGTERM gives the rest
# of its piece back; only rank 0 prints the summary; a certified sweep (2
# computing ranks) stores the single-process certified store.
# MPI is "yes" when the build has MPI (meson option mpi); otherwise, or
# without mpirun, the test is skipped (77) with the reason.
set -u
exe=$1
src=$2
have_mpi=$3
if [ "$have_mpi" != yes ]; then
  echo "SKIP: subspectra was built without MPI (meson option mpi: needs libopenmpi-dev)"
  exit 77
fi
if ! command -v mpirun >/dev/null; then
  echo "SKIP: mpirun not found (Debian's openmpi-bin, which ./run installs)"
  exit 77
fi
SS_EXPECT_TIMEOUT=240
. "$src/tests/ss_expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v sqlite3 >/dev/null || { echo "test_sweep_mpi: sqlite3 not installed (./run installs it)"; exit 1; }
. "$src/tests/sweep/ss_store_rows.sh"

# OpenMPI refuses to run as root unless told twice; the test may run as root
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# one machine: shared memory only (no probing of network interfaces), and no
# cross-process memory attach, which containers often forbid (ptrace)
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
# In a sanitizer build, no leak check in the ranks: OpenMPI leaves memory
# allocated by plugins it unloads in MPI_Finalize, reported from unknown
# modules that no suppression by library name can match.  AddressSanitizer
# and UBSan still check the ranks; the sweep code they share with the
# threaded sweep is leak-checked by the runs without mpirun (here and in
# test_sweep.sh).
mpi=(env "ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" mpirun --oversubscribe)

# the reference: the 23 links with 4..8 vertices and edges 3..8, one process
cases=(--scheme mlca --vertices 4..8 --edges 3..8)
expect 1 "29 cases of mlca .*29 computed.*1 thread; 0 already stored" \
  "$exe" sweep "${cases[@]}" --db "$tmp/ref.db" --jobs 1
total=$(q "$tmp/ref.db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ "$total" = 29 ] || fail "reference sweep stored $total rows, want 29 (23 links + 6 edges)"

# three ranks: the same rows; one summary (rank 0's), naming the 2 computing
# ranks; the JSON object once, on standard output; the sweep's exit status
# (1: some case fails) through mpirun
"${mpi[@]}" -n 3 "$exe" sweep "${cases[@]}" --db "$tmp/mpi.db" --jobs 1 --format json \
  >"$tmp/mpi.out" 2>"$tmp/mpi.err"
rc=$?
checks=$((checks + 1))
[ "$rc" = 1 ] || fail "mpirun -n 3 sweep: exit status $rc, want 1 ($(head -3 "$tmp/mpi.err"))"
same "mpirun -n 3 vs one process" "$tmp/ref.db" "$tmp/mpi.db"
checks=$((checks + 1))
n=$(grep -c "^subspectra sweep: 29 cases of mlca .*29 computed.*with 2 ranks of 1 thread" "$tmp/mpi.err")
[ "$n" = 1 ] || fail "mpirun -n 3: $n summary lines, want 1 (rank 0's): $(head -3 "$tmp/mpi.err")"
checks=$((checks + 1))
n=$(grep -c '"ranks":2' "$tmp/mpi.out")
[ "$n" = 1 ] && [ "$(wc -l <"$tmp/mpi.out")" = 1 ] ||
  fail "mpirun -n 3 --format json: want one object with \"ranks\":2: $(head -3 "$tmp/mpi.out")"
# the verdict counts of the summary are the stored rows' (recounted, not pasted)
nfail=$(q "$tmp/ref.db" "SELECT count(*) FROM cases WHERE verdict = 'fail'")
checks=$((checks + 1))
[ "$nfail" -gt 0 ] && grep -q "\"fail\":$nfail," "$tmp/mpi.out" ||
  fail "mpirun -n 3: JSON fail count is not the $nfail failing rows: $(cat "$tmp/mpi.out")"

# rerun into the complete store: nothing computed, everything found
expect 1 "29 cases .*\(0 computed.*2 ranks of 1 thread; 29 already stored\)" \
  "${mpi[@]}" -n 3 "$exe" sweep "${cases[@]}" --db "$tmp/mpi.db" --jobs 1

# one rank is the threaded sweep as it is without mpirun (its summary, no ranks)
expect 1 "29 cases of mlca .*29 computed, [0-9.]+ cases/s with 2 threads; 0 already stored" \
  "${mpi[@]}" -n 1 "$exe" sweep "${cases[@]}" --db "$tmp/one.db" --jobs 2
same "mpirun -n 1 vs one process" "$tmp/ref.db" "$tmp/one.db"

# a certified sweep as one MPI job with 2 computing ranks (mpirun -n 3; rank 0
# stores) stores what the single-process certified sweep stores,
# row for row with every certified flag; some verdicts are proven (not
# vacuously equal)
ccases=(--scheme mlca --vertices 4..8 --certify)
expect 1 "23 cases of mlca .*certified.*23 computed.*1 thread; 0 already stored" \
  "$exe" sweep "${ccases[@]}" --db "$tmp/cref.db" --jobs 1
expect 1 "23 cases of mlca .*certified.*23 computed.*2 ranks of 1 thread; 0 already stored" \
  "${mpi[@]}" -n 3 "$exe" sweep "${ccases[@]}" --db "$tmp/cmpi.db" --jobs 1
same_certified "certified: mpirun -n 3 vs one process" "$tmp/cref.db" "$tmp/cmpi.db"
n=$(q "$tmp/cmpi.db" "SELECT count(*) FROM result WHERE eigen_certified = 1 AND regularity_certified = 1")
checks=$((checks + 1))
[ "$n" -gt 10 ] || fail "certified sweep under mpirun: only $n of 23 rows proven"

# bad usage is reported once (by rank 0), exit 2
"${mpi[@]}" -n 3 "$exe" sweep --scheme mlca --vertices 4..9 --jobs 0 --db "$tmp/bad.db" \
  >"$tmp/bad.out" 2>&1
rc=$?
checks=$((checks + 1))
n=$(grep -c "subspectra sweep: --jobs '0' is not an integer" "$tmp/bad.out")
[ "$rc" = 2 ] && [ "$n" = 1 ] || fail "mpirun -n 3 sweep --jobs 0: status $rc, $n messages (want 2, 1)"

# the PID of rank R of the mpirun whose PID is M: the child whose
# environment says so
rank_pid() {
  local c
  for c in $(pgrep -P "$2"); do
    if tr '\0' '\n' <"/proc/$c/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$1"; then
      echo "$c"
      return
    fi
  done
}

# dynamic distribution: rank 1 stopped (SIGSTOP) mid-run holds only its piece
# (4 cases per thread); rank 2 computes everything else meanwhile (with fixed
# shares it would stop at about half)
db=$tmp/slow.db
"${mpi[@]}" -n 3 "$exe" sweep "${cases[@]}" --db "$db" --jobs 1 >/dev/null 2>&1 &
pid=$!
stopped=
n=0
for _ in $(seq 1 3000); do
  kill -0 "$pid" 2>/dev/null || break
  n=$(q "$db" "SELECT count(*) FROM result" 2>/dev/null || echo 0)
  if [ -z "$stopped" ] && [ "${n:-0}" -ge 2 ]; then
    stopped=$(rank_pid 1 "$pid")
    [ -n "$stopped" ] && kill -STOP "$stopped"
  fi
  [ -n "$stopped" ] && [ "${n:-0}" -ge $((total - 4)) ] && break
  sleep 0.02
done
[ -n "$stopped" ] && kill -CONT "$stopped"
wait "$pid"
rc=$?
checks=$((checks + 1))
[ -n "$stopped" ] && [ "${n:-0}" -ge $((total - 4)) ] && [ "$rc" = 1 ] ||
  fail "rank 1 stopped: $n of $total rows stored meanwhile (want >= $((total - 4))), status $rc"
same "rank 1 stopped for a while vs one process" "$tmp/ref.db" "$db"

# signal_rank1_after ROWS SIG DB PID [hold]: once DB holds ROWS results (while
# the job PID runs), send SIG to rank 1 of that job; prints rank 1's pid if
# sent.  With "hold", rank 2 is stopped (SIGSTOP) first, so that it cannot
# finish the whole sweep in the moment before mpirun ends the job: the small
# cases take milliseconds, and on an idle machine rank 2 used to store all 29
# rows between rank 1's SIGKILL and mpirun's reaction (3 runs of 5 here).
signal_rank1_after() {
  local rows=$1 sig=$2 db=$3 job=$4 hold=${5:-} n r h
  for _ in $(seq 1 1500); do
    kill -0 "$job" 2>/dev/null || return 0
    n=$(q "$db" "SELECT count(*) FROM result" 2>/dev/null || echo 0)
    if [ "${n:-0}" -ge "$rows" ]; then
      if [ -n "$hold" ]; then
        h=$(rank_pid 2 "$job")
        [ -n "$h" ] && kill -STOP "$h"
      fi
      r=$(rank_pid 1 "$job")
      [ -n "$r" ] && kill -"$sig" "$r" && echo "$r"
      return 0
    fi
    sleep 0.02
  done
}

# SIGTERM to rank 1 alone: it finishes its case in flight and gives the rest
# of its piece back; rank 2 computes everything else, so the store is
# complete; the job ends with rank 1's signal (143) or the sweep's status
db=$tmp/term.db
"${mpi[@]}" -n 3 "$exe" sweep "${cases[@]}" --db "$db" --jobs 1 >/dev/null 2>"$tmp/term.err" &
pid=$!
termed=$(signal_rank1_after 4 TERM "$db" "$pid")
wait "$pid"
checks=$((checks + 1))
[ -n "$termed" ] && grep -q "^subspectra sweep: 29 cases of mlca .*; 0 already stored" "$tmp/term.err" ||
  fail "SIGTERM to rank 1: the sweep did not report all 29 cases: $(head -3 "$tmp/term.err")"
same "rank 1 stopped by SIGTERM vs one process" "$tmp/ref.db" "$db"

# SIGKILL to a computing rank mid-run: mpirun ends the job; what rank 0 had
# stored stays, sound; the same command computes only the rest.  On the 29
# small cases above (about 5 ms each) rank 2 often finished the whole sweep
# between the poll that saw 8 rows and mpirun's reaction (3 runs of 5 on an
# idle machine stored all 29), so this check sweeps the 312 cases with up to
# 10 link vertices (about 2 s on one thread) and holds rank 2 (SIGSTOP) at
# the moment of the kill; mpirun's SIGKILL ends the stopped rank too
big=(--scheme mlca --vertices 4..10 --edges 3..8)
"$exe" sweep "${big[@]}" --db "$tmp/bigref.db" --jobs 1 >/dev/null 2>&1
btotal=$(q "$tmp/bigref.db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ "$btotal" = 312 ] || fail "reference sweep of k <= 10 stored $btotal rows, want 312"
db=$tmp/kill.db
"${mpi[@]}" -n 3 "$exe" sweep "${big[@]}" --db "$db" --jobs 1 >/dev/null 2>"$tmp/kill.err" &
pid=$!
killed=$(signal_rank1_after 8 KILL "$db" "$pid" hold)
wait "$pid"
rc=$?
n=$(q "$db" "SELECT count(*) FROM result")
checks=$((checks + 1))
[ -n "$killed" ] && [ "$rc" != 0 ] && [ "$n" -gt 0 ] && [ "$n" -lt "$btotal" ] ||
  fail "kill of rank 1: killed '${killed}', mpirun status $rc, $n of $btotal rows stored (want a partial store)"
expect 0 "^ok\$" sqlite3 "$db" "PRAGMA integrity_check"
expect 1 "312 cases .*\($((btotal - n)) computed.*2 ranks of 1 thread; $n already stored\)" \
  "${mpi[@]}" -n 3 "$exe" sweep "${big[@]}" --db "$db" --jobs 1
expect 0 "^$btotal\$" sqlite3 "$db" "SELECT count(*) FROM (SELECT DISTINCT scheme_id, kind, k, link FROM result)"
same "rank 1 killed and resumed vs one process" "$tmp/bigref.db" "$db"

expect_done test_sweep_mpi
