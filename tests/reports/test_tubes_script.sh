#!/usr/bin/env bash
# reports/tubes.sh (issue 34 section 3): a link list through analyze
# --psi-tubes — the icosahedron a certified pass judged on psi with all 120
# tube boxes proven, finding 1 a certified failure on psi; the counts per k on
# standard error; usage errors exit 2.
#
#   test_tubes_script.sh SUBSPECTRA SOURCE_ROOT
set -uo pipefail
exe=$1 src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() {
  echo "FAIL: $*"
  fails=$((fails + 1))
}
ok() { echo "ok: $*"; }

printf 'icosahedron\n8 bcdefgh,ahc,abhd,ache,adhf,aehg,afh,agfedcb\n' >"$tmp/links"
if "$src/reports/tubes.sh" --exe "$exe" --list "$tmp/links" >"$tmp/out" 2>"$tmp/err"; then
  ok "tubes.sh ran"
else
  fail "tubes.sh exit $?: $(cat "$tmp/err")"
fi
python3 - "$tmp/out" <<'PY' && ok "verdicts and tubes as proven" || fail "verdicts: $(cat "$tmp/out")"
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
assert len(rows) == 2, rows
ico, f1 = rows
assert ico["regularity"] == "pass" and ico["certified"] and ico["judged_on"] == "psi", ico
assert ico["tubes"]["proven"] == ico["tubes"]["boxes"] == 120, ico["tubes"]
assert f1["regularity"] == "fail" and f1["certified"] and f1["judged_on"] == "psi", f1
PY
grep -q "k = 8: 1 fail, certified (judged on psi)" "$tmp/err" && ok "counts per k" ||
  fail "counts: $(cat "$tmp/err")"
"$src/reports/tubes.sh" --exe "$exe" --max-k x >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && grep -q "expects an integer" "$tmp/err" && ok "bad --max-k: exit 2" ||
  fail "bad --max-k: $(cat "$tmp/err")"
"$src/reports/tubes.sh" --exe "$tmp/none" >/dev/null 2>"$tmp/err"
[ $? -eq 2 ] && ok "no executable: exit 2" || fail "no executable"
echo "tubes_script: $fails failed"
[ "$fails" -eq 0 ]
