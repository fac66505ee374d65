# ss_store_rows.sh — sourced by the sweep tests after ss_expect.sh: compare
# results stores row by row on every column a result's mathematics determines.
#   q DB SQL          sqlite3 (expect runs programs: call sqlite3 there)
#   rows DB           those columns of every result, in a fixed order
#   same NAME DB1 DB2 a check: equal rows, and not vacuously
#   same_certified NAME DB1 DB2  the same with injectivity and every
#                     certified flag too (for --certify stores)
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
rows_certified() { # rows, then injectivity and the certified flags
  q "$1" "SELECT s.identity, kind, k, link, eigen_certified, regularity_certified,
          injectivity, injectivity_reason, degree, injectivity_certified
          FROM result r JOIN scheme s ON s.id = r.scheme_id ORDER BY 1, 2, 3, 4"
}
same_certified() { # same_certified NAME DB1 DB2
  same "$@"
  checks=$((checks + 1))
  local a b
  a=$(rows_certified "$2")
  b=$(rows_certified "$3")
  [ -n "$a" ] && [ "$a" = "$b" ] ||
    fail "$1: certified flags differ ($(diff <(echo "$a") <(echo "$b") | head -3))"
}
