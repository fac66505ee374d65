#!/usr/bin/env bash
# reports/tubes.sh (issue 34 section 3): a link list through analyze
# --psi-tubes — the icosahedron a certified pass judged on psi with all 120
# tube boxes proven and injective on psi, finding 1 a certified failure on psi; the counts per k on
# standard error; the links chosen from the tables (the default and
# --net-folds, on tables made up here); usage errors exit 2.
#
#   test_tubes_script.sh SUBSPECTRA SOURCE_ROOT
set -uo pipefail
exe=$1 src=$2
. "$(dirname "$0")/../ss_expect.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
script=$src/reports/tubes.sh

printf 'icosahedron\n8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb\n' >"$tmp/links"
SS_EXPECT_TIMEOUT=240 expect 0 "k = 8: regularity 1 fail, certified \(judged on psi\)" \
  bash -c '"$0" --exe "$1" --list "$2" >"$3"' "$script" "$exe" "$tmp/links" "$tmp/out"
expect 0 "" python3 - "$tmp/out" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
assert len(rows) == 2, rows
ico, f1 = rows
assert ico["regularity"] == "pass" and ico["certified"] and ico["judged_on"] == "psi", ico
assert ico["tubes"]["proven"] == ico["tubes"]["boxes"] == 120, ico["tubes"]
assert f1["regularity"] == "fail" and f1["certified"] and f1["judged_on"] == "psi", f1
assert ico["injectivity"] == "pass" and ico["injectivity_certified"], ico
assert ico["injectivity_judged_on"] == "psi" and ico["psi_injectivity"]["proven"], ico
PY
# The choice of links, on tables made up here (no computation): the default
# takes the net's undecided MLCA vertex links with a passing eigenvalue
# condition and k <= K; --net-folds the net's certified folds that the psi
# table leaves undecided, and nothing else.
mkdir -p "$tmp/data"
python3 - "$tmp/data" <<'PY'
import csv, lzma, sys
head = ["identity", "scheme", "k", "case", "link", "class", "certified",
        "min_scaled_jacobian", "eigen_condition", "eigen_reason", "regularity",
        "regularity_reason", "injectivity", "injectivity_reason"]
def row(scheme, k, link, eigen, reg, cert, case="vertex"):
    return {"identity": scheme, "scheme": scheme, "k": k, "case": case,
            "link": "%d %s" % (k, link), "class": "", "certified": cert,
            "min_scaled_jacobian": "", "eigen_condition": eigen, "eigen_reason": "",
            "regularity": reg, "regularity_reason": "", "injectivity": "undecided",
            "injectivity_reason": ""}
net = [row("mlca", 12, "fold-psi-undecided", "pass", "fail", 1),
       row("mlca", 12, "fold-psi-fold", "pass", "fail", 1),
       row("mlca", 12, "fold-uncertified", "pass", "fail", 0),
       row("mlca", 12, "undecided", "pass", "undecided", 0),
       row("mlca", 12, "eigen-undecided", "undecided", "undecided", 0),
       row("mlca", 13, "fold-psi-undecided-k13", "pass", "fail", 1),
       row("tetoct", 12, "fold-psi-undecided", "pass", "fail", 1),
       row("mlca", 12, "edge-point", "pass", "undecided", 0, "edge-point")]
psi = [row("mlca", 12, "fold-psi-undecided", "pass", "undecided", 0),
       row("mlca", 12, "fold-psi-fold", "pass", "fail", 1),
       row("mlca", 12, "fold-uncertified", "pass", "undecided", 0),
       row("mlca", 13, "fold-psi-undecided-k13", "pass", "undecided", 0),
       row("tetoct", 12, "fold-psi-undecided", "pass", "undecided", 0)]
for name, rows in (("exhaustive-vertices-k4-13-not-passing.csv.xz", net),
                   ("exhaustive-vertices-psi-k4-13-not-passing.csv.xz", psi)):
    with lzma.open(sys.argv[1] + "/" + name, "wt", newline="") as f:
        w = csv.DictWriter(f, head)
        w.writeheader()
        w.writerows(rows)
PY
same() { # same WHAT GOT WANT
  checks=$((checks + 1))
  [ "$2" = "$3" ] || fail "$1: got '$2', want '$3'"
}
same "default choice: the net's undecided MLCA vertex links" \
  "$("$script" --exe "$exe" --data "$tmp/data" --max-k 12 --links-only 2>&1)" "12 undecided"
same "--net-folds: the certified net folds psi leaves undecided" \
  "$("$script" --exe "$exe" --data "$tmp/data" --max-k 12 --net-folds --links-only 2>&1)" \
  "12 fold-psi-undecided"
same "--net-folds --max-k 13 adds k = 13" \
  "$("$script" --exe "$exe" --data "$tmp/data" --max-k 13 --net-folds --links-only 2>&1)" \
  "12 fold-psi-undecided
13 fold-psi-undecided-k13"
expect 2 "cannot read" "$script" --exe "$exe" --data "$tmp/none" --links-only
expect 2 "expects an integer" "$script" --exe "$exe" --max-k x
expect 2 "--psi-depth expects an integer in 1..8" "$script" --exe "$exe" --psi-depth 0
expect 2 "no subspectra at" "$script" --exe "$tmp/none"
expect_done "tubes_script"
