#!/usr/bin/env bash
# test_jsr_cli.sh EXE — `subspectra jsr` from the outside: the JSON keys the
# issue names, the verdict agreeing with the bounds and the threshold, the
# edge threshold lambda3 = min(lambda1, 1/2), and exit status 2 with a message
# for bad usage.
set -u
exe=$1
SS_EXPECT_TIMEOUT=120
. "$(dirname "$0")/../ss_expect.sh"

expect_in 0 "Levin-Levin smoothness test" "" "$exe" jsr --help
expect_in 0 "jsr " "" "$exe" --help
expect_in 2 "--scheme is required" "" "$exe" jsr --face
expect_in 2 "give --face or --edge N" "" "$exe" jsr --scheme tetoct
expect_in 2 "give one of --face and --edge" "" "$exe" jsr --scheme tetoct --face --edge 4
expect_in 2 "--edge: expected a valence 3..64, not '2'" "" "$exe" jsr --scheme tetoct --edge 2
expect_in 2 "--depth: expected 1..12" "" "$exe" jsr --scheme tetoct --face --depth 0
expect_in 2 "--gap: expected a number in" "" "$exe" jsr --scheme tetoct --face --gap 2
expect_in 2 "--diagonals: expected bfs" "" "$exe" jsr --scheme boxspline --face --diagonals x
expect_in 2 "unknown scheme 'nope'" "" "$exe" jsr --scheme nope --face
expect_in 2 "the face case exists only for schemes with the tet/oct split" "" "$exe" jsr --scheme mlca --face
expect_in 2 "tet stars only" "" "$exe" jsr --scheme mlca --edge 4
expect_in 2 "defined around an edge" "" "$exe" jsr --scheme boxspline --face --diagonals skew
expect_in 2 "unexpected argument 'x'" "" "$exe" jsr --scheme tetoct --face x
# the face of tet/oct: C^2 (threshold 1/4), quadratics as the subspace
out=$("$exe" jsr --scheme tetoct --face --depth 3 --max-seconds 5 --format json)
checks=$((checks + 1))
python3 - "$out" <<'PY' || fail "tetoct face JSON: $out"
import json, sys
j = json.loads(sys.argv[1])
for k in ("lower", "upper", "threshold", "rho_k", "verdict", "certified"):
    assert k in j, k
assert j["threshold"] == 0.25 and len(j["rho_k"]) == 3 and len(j["rho_k_2"]) == 3
assert j["subspace"] == 10 and j["subspace_basis"] == "quadratics"
assert j["lower"] <= j["upper"] <= j["rho_k"][2] + 1e-12
want = "pass" if j["upper"] < 0.25 else "fail" if j["lower"] >= 0.25 else "undecided"
assert j["verdict"] == want
assert abs(j["theta"][9] - 0.25) < 1e-10 and abs(j["theta"][1] - 0.5) < 1e-10
PY
# an edge: threshold lambda3 = min(lambda1, 1/2), lambda1 < 1/2 for valence 3
out=$("$exe" jsr --scheme tetoct --edge 3 --depth 3 --max-seconds 2 --format json)
checks=$((checks + 1))
python3 - "$out" <<'PY' || fail "tetoct edge 3 JSON: $out"
import json, sys
j = json.loads(sys.argv[1])
assert j["maps"] == 2 and j["subspace"] == 4
assert j["lambda1"] < 0.5 and j["threshold"] == j["lambda1"]
assert sorted(j["theta"], reverse=True)[0] == 1 or abs(j["theta"][0] - 1) < 1e-10
PY
expect_in 2 "--norm: expected auto, inf, 2, ellipsoid or polytope, not 'l1'" "" "$exe" jsr --scheme tetoct --face --norm l1
# edge 10: undecided in the inf- and 2-norms ([0.4948, 0.5271] against 1/2);
# the fitted ellipsoidal norm is extremal there (JSR = rho(Y_1)): the bounds
# meet to the gap at short words and prove the pass
out=$("$exe" jsr --scheme tetoct --edge 10 --depth 3 --norm ellipsoid --max-seconds 60 --format json)
checks=$((checks + 1))
python3 - "$out" <<'PY' || fail "tetoct edge 10 ellipsoid JSON: $out"
import json, sys
j = json.loads(sys.argv[1])
assert j["norm"] == "ellipsoid" and j["converged"] and j["certified"]
assert j["lower"] <= j["upper"] <= j["lower"] * (1 + 1e-3)
assert j["threshold"] == 0.5 and j["upper"] < 0.5 and j["verdict"] == "pass"
PY
# --fit-words K: the ellipsoid fitted to the products of length K.  Bad K
# is refused; K = 1 is the default (edge 3: the fit converges long before
# its deadline, so the two runs are the same computation); K = 2 on the
# face and on edge 3 gives proven bounds (lower <= upper) with the key.
expect_in 2 "--fit-words: expected 1..5, not '0'" "" "$exe" jsr --scheme tetoct --face --fit-words 0
expect_in 2 "--fit-words: expected 1..5, not '6'" "" "$exe" jsr --scheme tetoct --face --fit-words 6
expect_in 2 "--fit-words: expected 1..5, not 'x'" "" "$exe" jsr --scheme tetoct --face --fit-words x
expect_in 2 "it needs --norm ellipsoid or auto, not inf" "" "$exe" jsr --scheme tetoct --edge 3 --norm inf --fit-words 2
expect_in 2 "it needs --norm ellipsoid or auto, not polytope" "" "$exe" jsr --scheme tetoct --face --norm polytope --fit-words 3
a=$("$exe" jsr --scheme tetoct --edge 3 --depth 3 --norm ellipsoid --max-seconds 60 --format json)
b=$("$exe" jsr --scheme tetoct --edge 3 --depth 3 --norm ellipsoid --max-seconds 60 --fit-words 1 --format json)
c=$("$exe" jsr --scheme tetoct --edge 3 --depth 3 --norm ellipsoid --max-seconds 60 --fit-words 2 --format json)
checks=$((checks + 1))
python3 - "$a" "$b" "$c" <<'PY' || fail "tetoct edge 3 --fit-words: $a $b $c"
import json, sys
a, b, c = (json.loads(x) for x in sys.argv[1:])
assert a["fit_words"] == 1 and b["fit_words"] == 1 and c["fit_words"] == 2
assert (a["lower"], a["upper"], a["bnb_depth"]) == (b["lower"], b["upper"], b["bnb_depth"])
assert c["norm"] == "ellipsoid" and c["certified"] and c["converged"]
assert c["lower"] <= c["upper"] <= c["lower"] * (1 + 1e-3) and c["verdict"] == "pass"
PY
out=$("$exe" jsr --scheme tetoct --face --depth 3 --max-seconds 5 --fit-words 2 --format json)
checks=$((checks + 1))
python3 - "$out" <<'PY' || fail "tetoct face --fit-words 2 JSON: $out"
import json, sys
j = json.loads(sys.argv[1])
assert j["fit_words"] == 2 and j["lower"] <= j["upper"] and j["certified"]
want = "pass" if j["upper"] < 0.25 else "fail" if j["lower"] >= 0.25 else "undecided"
assert j["verdict"] == want
PY
# box-spline faces with the diagonals of Algorithm 2 have the eigenvalue
# 0.512 > 1/2: the reduction does not apply, exit 1 with the spectrum
expect_in 1 "are not 1, 1/2 x3, 1/4 x6" "" "$exe" jsr --scheme boxspline --face --depth 2 --max-seconds 1
# --max-seconds holds in the products for rho_k too (issue 35, item 12: depth
# 12 ran for minutes): the run stops in time, says which lengths are complete,
# and their rho_k are those of an unlimited run to that depth
t0=$(date +%s)
cut=$("$exe" jsr --scheme tetoct --face --depth 12 --max-seconds 1 --format json)
t1=$(date +%s)
checks=$((checks + 1))
[ $((t1 - t0)) -lt 30 ] || fail "jsr --depth 12 --max-seconds 1 took $((t1 - t0)) s"
d=$(python3 -c 'import json,sys; print(json.loads(sys.argv[1])["depth_complete"])' "$cut")
full=$("$exe" jsr --scheme tetoct --face --depth "$d" --max-seconds 5 --format json)
checks=$((checks + 1))
python3 - "$cut" "$full" <<'PY' || fail "time-limited rho_k: $cut / $full"
import json, sys
c, f = (json.loads(x) for x in sys.argv[1:])
assert c["stopped_by"] == "max-seconds" and c["depth"] == 12
d = c["depth_complete"]
assert 1 <= d < 12 and c["cut_length"] == d + 1
assert 0 <= c["cut_words"] < c["cut_of"] == 4 ** (d + 1)
assert c["rho_k"] == f["rho_k"] and c["rho_k_2"] == f["rho_k_2"] and len(c["rho_k"]) == d
assert "stopped_by" not in f and "cut_length" not in f
assert c["lower"] <= c["upper"] <= min(c["rho_k"]) * (1 + 1e-9)
PY
expect_in 0 "were cut short after" "" "$exe" jsr --scheme tetoct --face --depth 12 --max-seconds 1
expect_in 2 "below 1e7 \(the cap\), not '1e7'" "" "$exe" jsr --scheme tetoct --face --max-seconds 1e7
# --diagonals only where the rule reads them (tet/oct's does not: it changed
# rho_k without meaning anything)
expect_in 2 "scheme tetoct reads no major diagonals" "" "$exe" jsr --scheme tetoct --edge 5 --diagonals skew
expect_in 2 "scheme tetoct reads no major diagonals" "" "$exe" jsr --scheme tetoct --face --diagonals bfs
# where the reduction does not apply, --format json still prints one object
out=$("$exe" jsr --scheme boxspline --face --depth 2 --max-seconds 1 --format json)
rc=$?
checks=$((checks + 1))
[ "$rc" = 1 ] || fail "boxspline face json: exit $rc"
python3 - "$out" <<'PY' || fail "boxspline face JSON when the reduction does not apply: $out"
import json, sys
j = json.loads(sys.argv[1])
assert j["applies"] is False and j["verdict"] == "n/a"
assert "1, 1/2 x3, 1/4 x6" in j["reason"]
assert j["lower"] is None and j["upper"] is None and j["rho_k"] is None
PY
# slashes as the other commands write them (json-c escapes them as \/ unless
# told not to): the edge's threshold name holds one
out=$("$exe" jsr --scheme tetoct --edge 5 --depth 2 --format json)
checks=$((checks + 1))
grep -qF '"threshold_name":"lambda3 = lambda1 (< 1/2)"' <<<"$out" && ! grep -qF '\/' <<<"$out" ||
  fail "jsr --format json escapes slashes: $out"
expect_done test_jsr_cli
