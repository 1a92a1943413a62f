#!/usr/bin/env bash
# Outputs that cannot be written as asked, integers that are not decimal, bounds of advise's
# survey, JSON followed by a NUL byte, SIGHUP during a run, and output files that are only ever
# whole under their own name.
# Usage: hostile_inputs.sh PROGRAM DATA WORK
PROGRAM=$1 DATA=$2 WORK=$3
source "$(dirname "$0")/common.sh"
rm -rf "$WORK" && mkdir -p "$WORK"

# A FIFO with no reader as --csv: refused at once instead of blocking in open().
mkfifo "$WORK/out.fifo"
expect csv-fifo 2 "cannot write --csv file '.*out.fifo': not a regular file or device \(a FIFO or socket\)$" -- \
  run --scene pendulum --steps 10 --csv "$WORK/out.fifo"
# An empty file name writes nothing silently no more.
expect csv-empty 2 '^particle-lab: --csv: expected a file name, got ""$' -- run --scene pendulum --steps 10 --csv ""
expect trajectory-empty 2 '^particle-lab: --trajectory: expected a file name, got ""$' -- \
  run --scene pendulum --steps 10 --trajectory ""
# --csv naming the file stdout is redirected to: the summary would overwrite its header.
expect_stdout_clash() {
  local got=0
  timeout 60 "$PROGRAM" run --scene pendulum --steps 10 --csv /dev/stdout >"$WORK/clash.out" 2>"$WORK/clash.err" || got=$?
  if [ "$got" = 2 ] && grep -q 'also the standard output' "$WORK/clash.err" && [ "$(wc -l <"$WORK/clash.err")" = 1 ]; then
    pass csv-is-stdout
  else
    fail "csv-is-stdout: exit $got: $(head -c 300 "$WORK/clash.err")"
  fi
}
expect_stdout_clash
# Both tables on standard output would interleave: refused before any output.
expect csv-and-trajectory-stdout 2 "^particle-lab: --csv and --trajectory cannot both write to standard output \('-'\); give one of them a file name$" -- \
  run --scene pendulum --steps 10 --csv - --trajectory -
# An infinite number is named as such.
expect advise-horizon-inf 2 '^particle-lab: --horizon: value must be finite and > 0, got inf$' -- \
  advise --scene pendulum --error 1e-3 --horizon inf
# Integers are decimal: a leading zero or 0x is refused, not read as octal or hex.
expect substeps-octal 2 'substeps: expected a decimal integer in \[1, 100000\] \(no leading zeros or 0x\), got 010$' -- \
  run --scene cloth --integrator xpbd --steps 1 --substeps 010
expect substeps-hex 2 'substeps: expected a decimal integer in \[1, 100000\] \(no leading zeros or 0x\), got 0x10$' -- \
  run --scene cloth --integrator xpbd --steps 1 --substeps 0x10
# advise: a horizon whose reference would not fit memory, a reference tolerance below rounding.
expect advise-horizon 2 'horizon 1e\+300 s needs .* reference samples .*more than the limit of 2.5e\+07$' -- \
  advise --scene pendulum --error 1e-3 --horizon 1e300
expect advise-certify-starts 2 '^particle-lab: --certify-starts: expected a decimal integer in \[0, 1000\], got -1$' -- \
  advise --scene pendulum --error 1e-3 --horizon 1 --certify-starts -1
expect advise-certify-starts-octal 2 '^particle-lab: --certify-starts: expected a decimal integer in \[0, 1000\] \(no leading zeros or 0x\), got 010$' -- \
  advise --scene pendulum --error 1e-3 --horizon 1 --certify-starts 010
expect advise-reference-tolerance 2 '^particle-lab: --reference-tolerance: value must be in \[1e-13, 1\], got 1e-300$' -- \
  advise --scene pendulum --error 1e-3 --reference-tolerance 1e-300
# The summary on a full disk is a failed output (exit 4), as export's file is.
if [ -w /dev/full ]; then
  got=0
  timeout 60 "$PROGRAM" run --scene pendulum --steps 10 >/dev/full 2>"$WORK/full.err" || got=$?
  if [ "$got" = 4 ] && grep -q 'cannot write the standard output' "$WORK/full.err"; then pass run-stdout-full
  else fail "run-stdout-full: exit $got: $(head -c 300 "$WORK/full.err")"; fi
fi
# Valid JSON, a NUL byte, then garbage: rejected as trailing garbage is.
printf '{"particles": []}\0garbage' >"$WORK/nul.json"
expect nul-then-garbage 2 'parse error at line 1, column 18: a NUL byte' -- run --scene-file "$WORK/nul.json" --steps 1

# A setting the engine refuses names the file and the field's JSON path; a normal is a direction.
scene() { printf '{"particles": [{"position": [0, 1], "mass": 1}], %s}' "$2" >"$WORK/$1.json"; }
scene substeps0 '"integratorSettings": {"substeps": 0}'
expect scene-substeps-0 2 '^particle-lab: .*substeps0.json: \$\.integratorSettings\.substeps: expected an integer in \[1, 100000\], got 0$' -- \
  run --scene-file "$WORK/substeps0.json" --steps 1
scene tolerance '"integratorSettings": {"tolerance": 9.9e-14}'
expect scene-tolerance 2 '^particle-lab: .*tolerance.json: \$\.integratorSettings\.tolerance: integrator tolerance must be >= 1e-13 .*, got 9\.9e-14$' -- \
  run --scene-file "$WORK/tolerance.json" --steps 1
# A scene whose extent overflows a double (particles and view from -1e308 to 1e308) is refused by name
# before any output, not reported as a bad internal length.
scene vast '"view": {"min": [-1e308, -1e308], "max": [1e308, 1e308]}'
expect scene-vast 2 "^particle-lab: scene file '.*vast.json': its particles and view span more than a double holds" -- \
  run --scene-file "$WORK/vast.json" --steps 1 --csv "$WORK/vast.csv"
[ -e "$WORK/vast.csv" ] && fail "scene-vast: the refused run created its --csv file"
scene huge-normal '"colliders": [{"type": "halfPlane", "point": [0, 0], "normal": [1e308, 1e308]}]'
if "$PROGRAM" run --scene-file "$WORK/huge-normal.json" --steps 1 >/dev/null 2>"$WORK/huge-normal.err"; then
  pass scene-huge-normal
else
  fail "scene-huge-normal: refused: $(head -c 300 "$WORK/huge-normal.err")"
fi
scene zero-normal '"colliders": [{"type": "halfPlane", "point": [0, 0], "normal": [0, 0]}]'
expect scene-zero-normal 2 '^particle-lab: .*zero-normal.json: \$\.colliders\[0\]\.normal: expected a non-zero vector, got \[0,0\]$' -- \
  run --scene-file "$WORK/zero-normal.json" --steps 1
# A right-to-left override (U+202E) in a name is shown escaped, in the summary and in an error.
printf '{"name": "report\u202eFDP.exe", "particles": [{"position": [0, 0], "mass": 1}]}' >"$WORK/bidi.json"
got=0
"$PROGRAM" run --scene-file "$WORK/bidi.json" --steps 1 >"$WORK/bidi.out" 2>&1 || got=$?
if [ "$got" = 0 ] && grep -Fq 'report\u202eFDP.exe with' "$WORK/bidi.out" && ! grep -q $'\xe2\x80\xae' "$WORK/bidi.out"; then
  pass bidi-name-summary
else
  fail "bidi-name-summary: exit $got: $(od -c "$WORK/bidi.out" | head -3)"
fi
expect bidi-name-error 2 "unknown scene 'report\\\\u202eFDP'" -- run --scene $'report\xe2\x80\xaeFDP' --steps 1

# SIGHUP during a run stops it at a step boundary, as SIGTERM does (exit 130, complete rows).
"$PROGRAM" run --scene cloth --param width=20 --param height=20 --steps 100000000 --csv "$WORK/hup.csv" \
  >/dev/null 2>"$WORK/hup.err" &
pid=$!
if wait_for_rows "$WORK/hup.csv.partial" 3; then  # written under its temporary name until closed
  kill -HUP "$pid"
  code=0
  wait_for "$pid" 10 || code=$?
  if [ "$code" = 130 ] && complete_csv "$WORK/hup.csv"; then pass sighup
  else fail "sighup: exit $code, csv complete: $(complete_csv "$WORK/hup.csv" && echo yes || echo no)"; fi
else
  kill -KILL "$pid" 2>/dev/null
  fail "sighup: the run wrote no rows"
fi

# An output file of the asked name is only ever whole: while a run writes it, it is
# TRAJ.partial (TRAJ itself absent, or still the previous complete file); SIGTERM ends
# the run with TRAJ complete and no .partial; SIGKILL mid-write leaves the previous TRAJ
# untouched and only the .partial cut.
traj=$WORK/whole.trajectory.csv
long_run() {
  "$PROGRAM" run --scene cloth --param width=40 --param height=40 --steps 100000000 --trajectory "$traj" \
    >/dev/null 2>"$WORK/whole.err" &
  pid=$!
}
long_run
if wait_for_rows "$traj.partial" 2000; then
  [ -e "$traj" ] && fail "whole-file: '$traj' exists while it is being written"
  kill -TERM "$pid"
  code=0
  wait_for "$pid" 30 || code=$?
  if [ "$code" = 130 ] && [ ! -e "$traj.partial" ] && complete_csv "$traj"; then pass whole-file-sigterm
  else fail "whole-file-sigterm: exit $code, partial left: $([ -e "$traj.partial" ] && echo yes || echo no)"; fi
else
  kill -KILL "$pid" 2>/dev/null
  fail "whole-file-sigterm: the run wrote no rows"
fi
cp "$traj" "$WORK/previous.csv"
long_run
if wait_for_rows "$traj.partial" 2000; then
  cmp -s "$traj" "$WORK/previous.csv" || fail "whole-file: the previous file changed while the new one is written"
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null
  if cmp -s "$traj" "$WORK/previous.csv"; then pass whole-file-sigkill
  else fail "whole-file-sigkill: '$traj' is not the previous complete file"; fi
else
  kill -KILL "$pid" 2>/dev/null
  fail "whole-file-sigkill: the run wrote no rows"
fi
# CG whose work passes the solver's bound falls back to the direct solve and says so once.
cat >"$WORK/cg-chain.json" <<'JSON'
{"solver": {"method": "cg", "preconditioner": "none", "warmStart": false, "maxCgWork": 20},
 "dt": 0.01,
 "particles": [{"position": [0, 0], "mass": 1, "pinned": true}, {"position": [0.5, 0], "mass": 1},
               {"position": [1, 0.1], "mass": 1}, {"position": [1.5, 0], "mass": 1}],
 "forces": [{"type": "gravity", "acceleration": [0, -9.81]}],
 "constraints": [{"type": "rod", "particles": [0, 1], "length": 0.5},
                 {"type": "rod", "particles": [1, 2], "length": 0.5},
                 {"type": "rod", "particles": [2, 3], "length": 0.5}]}
JSON
expect cg-work-bound 0 "^particle-lab: note: CG on 3 constraints passed its work bound \(20 products of J's entries in one solve\): solved directly \(LDLT\) instead, from step 1$" -- \
  run --scene-file "$WORK/cg-chain.json" --integrator rk4 --steps 20
finish
