# Shared by the shell tests of particle-lab: sourced with PROGRAM, DATA and WORK set.
set -u
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

# expect NAME CODE STDERR_REGEX -- ARGS...: runs particle-lab (at most 60 s) and checks its exit
# code and that stderr is exactly one line matching the regex. The lab shows progress on stderr
# first: with LAST_LINE=1, only the last line of stderr must be the error.
expect() {
  local name=$1 code=$2 regex=$3
  shift 4
  local lines=cat
  [ "${LAST_LINE:-0}" = 1 ] && lines="tail -n 1"
  local got=0
  timeout 60 "$PROGRAM" "$@" >"$WORK/$name.out" 2>"$WORK/$name.err" || got=$?
  if [ "$got" != "$code" ]; then fail "$name: exit $got, expected $code ($(head -c 300 "$WORK/$name.err"))"; return; fi
  if [ "$($lines "$WORK/$name.err" | wc -l)" != 1 ] || ! $lines "$WORK/$name.err" | grep -Eq -- "$regex"; then
    fail "$name: stderr is not one line matching '$regex': $(head -c 300 "$WORK/$name.err")"; return
  fi
  pass "$name"
}

# complete_csv FILE: every row has the header's number of fields and the file ends with a newline.
complete_csv() {
  [ -s "$1" ] && [ "$(tail -c 1 "$1" | od -An -c | tr -d ' ')" = '\n' ] &&
    awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$1"
}

# wait_for PID SECONDS: waits for the process to end; kills it and returns 124 after SECONDS.
wait_for() {
  local pid=$1 left=$(($2 * 10))
  while kill -0 "$pid" 2>/dev/null; do
    if [ $left -le 0 ]; then kill -KILL "$pid"; wait "$pid" 2>/dev/null; return 124; fi
    sleep 0.1
    left=$((left - 1))
  done
  local code=0
  wait "$pid" || code=$?
  return $code
}

# wait_for_rows FILE ROWS [PID [SECONDS]]: waits (at most SECONDS, default 30) until FILE has
# at least ROWS lines; fails at once if process PID has ended first.
wait_for_rows() {
  local left=$((${4:-30} * 10)) lines
  while true; do
    lines=0; [ -f "$1" ] && lines=$(wc -l 2>/dev/null <"$1"); lines=${lines:-0}
    [ -f "$1" ] && [ "$lines" -ge "$2" ] && return 0
    [ $left -le 0 ] && return 1
    [ -n "${3:-}" ] && ! kill -0 "$3" 2>/dev/null && return 1
    sleep 0.1
    left=$((left - 1))
  done
}

finish() {
  if [ "$failures" -gt 0 ]; then echo "$failures failure(s)"; exit 1; fi
  echo "all passed"
  exit 0
}
