#!/usr/bin/env bash
# The function-size check finds a function one line over its threshold and
# passes one at it, counts a signature over several lines and a lambda inside
# with their function, and refuses bad use.
# Usage: function_size.sh SCRIPT WORK
SCRIPT=$1 WORK=$2
rm -rf "$WORK" && mkdir -p "$WORK/src"
status=0
fail() { echo "FAIL: $*"; status=1; }
# A function whose body has `n` lines after its opening line (the last one its closing brace).
body() {
  local name=$1 n=$2 k
  printf 'int %s(int a,\n        int b) {\n' "$name"
  printf '  auto f = [&](int x) {\n    return x + a;\n  };\n'
  for ((k = 4; k < n; k++)); do printf '  a += f(b);  // line %d\n' "$k"; done
  printf '}\n\n'
}
{ body atThreshold 60; body overThreshold 61; } >"$WORK/src/sizes.cpp"
out=$(bash "$SCRIPT" --lines 60 "$WORK/src" 2>&1); code=$?
[ "$code" = 1 ] || fail "expected exit 1, got $code: $out"
grep -q "sizes.cpp:[0-9]*: function 'overThreshold': 61 lines (threshold 60)" <<<"$out" || fail "over: $out"
grep -q "atThreshold" <<<"$out" && fail "a function at the threshold was reported: $out"
out=$(bash "$SCRIPT" --lines 61 "$WORK/src" 2>&1); code=$?
[ "$code" = 0 ] && grep -q "no function over 61 lines in 1 file" <<<"$out" || fail "at 61: exit $code: $out"
out=$(bash "$SCRIPT" --lines 60 --exclude sizes.cpp "$WORK/src" 2>&1); code=$?
[ "$code" = 2 ] || fail "everything excluded: exit $code: $out"
out=$(bash "$SCRIPT" --lines 0 "$WORK/src" 2>&1); code=$?
[ "$code" = 2 ] || fail "--lines 0: exit $code: $out"
[ "$status" = 0 ] && echo "function-size check: ok"
exit $status
