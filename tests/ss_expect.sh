# ss_expect.sh — checking helpers of the shell tests (sourced, not run).
#
#   expect STATUS PATTERN CMD...           run CMD; its exit status must be
#                                          STATUS and its stdout+stderr must
#                                          match the extended regex PATTERN
#   expect_in STATUS PATTERN STDIN CMD...  the same, feeding STDIN to CMD
#   fail MESSAGE...                        record a failed check
#   expect_done NAME                       print "NAME: N checks, M failed";
#                                          true iff checks ran and none failed
# Each command may run SS_EXPECT_TIMEOUT seconds (default 60) times
# SS_TIMEOUT_MULTIPLIER (default 1; `./run sanitize` sets 4: the sanitizers slow
# everything down).
checks=0
failed=0

fail() {
  failed=$((failed + 1))
  echo "FAILED: $*" >&2
}

expect() {
  local want=$1 pat=$2
  shift 2
  checks=$((checks + 1))
  local out rc
  out=$(timeout "$(( ${SS_EXPECT_TIMEOUT:-60} * ${SS_TIMEOUT_MULTIPLIER:-1} ))" "$@" 2>&1)
  rc=$?
  if [ "$rc" -ne "$want" ] || ! grep -Eq -- "$pat" <<<"$out"; then
    fail "$* -> status $rc (want $want): $(head -5 <<<"$out")"
  fi
}

expect_in() {
  local want=$1 pat=$2 input=$3
  shift 3
  checks=$((checks + 1))
  local out rc
  out=$(printf '%s' "$input" | timeout "$(( ${SS_EXPECT_TIMEOUT:-60} * ${SS_TIMEOUT_MULTIPLIER:-1} ))" "$@" 2>&1)
  rc=$?
  if [ "$rc" -ne "$want" ] || ! grep -Eq -- "$pat" <<<"$out"; then
    fail "$* <<< '$input' -> status $rc (want $want): $(head -3 <<<"$out")"
  fi
}

expect_done() {
  echo "$1: $checks checks, $failed failed"
  [ "$failed" -eq 0 ] && [ "$checks" -gt 0 ]
}
