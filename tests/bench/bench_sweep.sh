#!/usr/bin/env bash
# bench_sweep.sh EXE [KMAX] — the sweep benchmark (issue 7), measured side by
# side in one run:
#   (a) an MLCA vertex sweep over every link with 4..KMAX vertices (default 12:
#       9150 links) into a fresh store, with 1 thread and with 2 threads:
#       cases per second and the speed-up (target >= 1.8 on 2 cores);
#   (b) the time per case at k = 12, 14 and 16 on sampled links (random links
#       of `enumerate random`, 1 thread), and what a whole sweep of those k
#       would take, so a user can plan an overnight run.
# About 8 minutes on a 2-core machine with KMAX = 12; pass 10 for a quick look.
# Measured 2026-12-03 13:43 UTC on the idle 2-core machine (load 0.7, nothing
# else running), KMAX = 11 (1,555 links): 1 thread 50.9 s (30.6 cases/s),
# 2 threads 26.6 s (58.5 cases/s), speed-up 1.91, stores identical; sampled
# random links: k = 12 22.8 ms, k = 14 33.9 ms, k = 16 36.4 ms per case.
set -euo pipefail
exe=$1
kmax=${2:-12}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v sqlite3 >/dev/null || { echo "bench_sweep: needs sqlite3 (./run installs it)"; exit 1; }

now() { date +%s.%N; }
calc() { awk "BEGIN { print ($*) }"; } # floating-point arithmetic without bc
run() { # run JOBS: seconds for the whole sweep into a fresh store
  local t0 t1
  t0=$(now)
  "$exe" sweep --scheme mlca --vertices 4.."$kmax" --db "$tmp/j$1.db" --jobs "$1" 2>/dev/null || [ $? -eq 1 ]
  t1=$(now)
  calc "$t1 - $t0"
}

cases=$("$exe" enumerate links --vertices 4.."$kmax" --count | awk -F'\t' '!/^#/ {s += $2} END {print s}')
echo "sweep benchmark: MLCA, every vertex link with 4..$kmax vertices ($cases cases), $(nproc) processors"
t1=$(run 1)
t2=$(run 2)
r1=$(calc "$cases / $t1")
r2=$(calc "$cases / $t2")
sp=$(calc "$t1 / $t2")
printf '  1 thread : %7.1f s  %7.1f cases/s\n' "$t1" "$r1"
printf '  2 threads: %7.1f s  %7.1f cases/s\n' "$t2" "$r2"
printf '  speed-up %.2f (target >= 1.8 on 2 cores): %s\n' "$sp" \
  "$(calc "$sp >= 1.8 ? \"met\" : \"NOT met\"")"
same=$(diff <(sqlite3 "$tmp/j1.db" "SELECT kind,k,link,eigenvalues,regularity,min_scaled_jacobian FROM result ORDER BY 1,2,3") \
            <(sqlite3 "$tmp/j2.db" "SELECT kind,k,link,eigenvalues,regularity,min_scaled_jacobian FROM result ORDER BY 1,2,3") >/dev/null && echo identical || echo DIFFERENT)
echo "  stores of the two runs: $(sqlite3 "$tmp/j2.db" "SELECT count(*) FROM result") rows each, $same"
echo "  per k (1 thread, from the store's per-case times):"
sqlite3 -separator ' ' "$tmp/j1.db" \
  "SELECT k, count(*), 1000*avg(seconds), 1000*max(seconds) FROM result GROUP BY k" |
  awk '{printf "    k = %2d: %5d cases, %7.1f ms per case (max %6.1f)\n", $1, $2, $3, $4}'

echo "time per case on sampled links (1 thread; random links, seed 1):"
declare -A all=([12]=7595 [13]=49566 [14]=339722 [15]=2406841 [16]=17490241)
for k in 12 14 16; do
  n=$([ "$k" -le 14 ] && echo 20 || echo 10)
  "$exe" enumerate random --vertices "$k" --samples "$n" --seed 1 |
    "$exe" sweep --scheme mlca --links - --db "$tmp/k$k.db" --jobs 1 2>/dev/null || [ $? -eq 1 ]
  read -r cnt avg mx < <(sqlite3 -separator ' ' "$tmp/k$k.db" "SELECT count(*), avg(seconds), max(seconds) FROM result")
  secs=$(calc "${all[$k]} * $avg / 2")
  if [ "$(calc "$secs < 3600")" = 1 ]; then
    span=$(printf '%.0f min' "$(calc "$secs / 60")")
  else
    span=$(printf '%.1f h' "$(calc "$secs / 3600")")
  fi
  printf '  k = %d: %2d links, %6.1f ms per case (max %6.1f); all %d links at k = %d: about %s with 2 threads\n' \
    "$k" "$cnt" "$(calc "$avg * 1000")" "$(calc "$mx * 1000")" "${all[$k]}" "$k" "$span"
done
