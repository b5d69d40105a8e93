# Sourced by the tools' shell tests: check NAME EXPECTED_CODE PATTERN -- command... runs the
# command, and fails the test (fail=1) unless it exits with EXPECTED_CODE and its output holds
# PATTERN. Needs $tmp (a scratch folder) set by the caller.
fail=0
check() {
  local name=$1 want=$2 pattern=$3; shift 4
  "$@" > "$tmp/out" 2>&1; local got=$?
  if [ "$got" != "$want" ] || ! grep -q -- "$pattern" "$tmp/out"; then
    echo "FAIL $name: exit $got (want $want), pattern '$pattern' in:"; sed 's/^/    /' "$tmp/out"; fail=1
  else echo "ok   $name"; fi
}
