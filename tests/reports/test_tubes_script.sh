#!/usr/bin/env bash
# reports/tubes.sh (issue 34 section 3): a link list through analyze
# --psi-tubes — the icosahedron a certified pass judged on psi with all 120
# tube boxes proven and injective on psi, finding 1 a certified failure on psi; the counts per k on
# standard error; usage errors exit 2.
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
expect 2 "expects an integer" "$script" --exe "$exe" --max-k x
expect 2 "--psi-depth expects an integer in 1..8" "$script" --exe "$exe" --psi-depth 0
expect 2 "no subspectra at" "$script" --exe "$tmp/none"
expect_done "tubes_script"
