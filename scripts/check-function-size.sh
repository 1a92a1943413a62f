#!/usr/bin/env bash
# Functions longer than a line threshold in the .cpp files of the given
# directories. A function's length is the lines of its body after the line
# that opens it, down to and including its closing brace, blank and comment
# lines included (clang-tidy's readability-function-size LineThreshold counts
# the same: over the laboratory, the runner and the demo, both list the same
# functions with the same counts at thresholds 20 and 40). Universal Ctags
# finds each function definition (its name's line and its closing brace's
# line; a lambda counts within its function); the body opens at the first "{"
# from the name's line on. Prints every offender as
#   path:line: function 'name': N lines (threshold T)
# and exits 1 if there is one, 0 if none, 2 on bad use.
#   bash scripts/check-function-size.sh [--lines N] [--exclude FILE]... DIR...
# (default --lines 60; --exclude leaves out one file, by its path as given or
# its name, and may be repeated; CTAGS names the program, default ctags).
set -euo pipefail
usage() { echo "usage: check-function-size.sh [--lines N] [--exclude FILE]... DIR..." >&2; exit 2; }
lines=60
excludes=()
dirs=()
while (($#)); do
  case "$1" in
    --lines) (($# >= 2)) || usage; lines=$2; shift 2 ;;
    --exclude) (($# >= 2)) || usage; excludes+=("$2"); shift 2 ;;
    -*) usage ;;
    *) dirs+=("$1"); shift ;;
  esac
done
((${#dirs[@]})) || usage
[[ "$lines" =~ ^[1-9][0-9]*$ ]] || { echo "check-function-size: --lines must be a positive integer, got '$lines'" >&2; exit 2; }
ctags=${CTAGS:-ctags}
"$ctags" --version 2>/dev/null | grep -q "Universal Ctags" ||
  { echo "check-function-size: $ctags is not Universal Ctags (Debian: universal-ctags)" >&2; exit 2; }

excluded() {
  local file=$1 skip
  for skip in ${excludes[@]+"${excludes[@]}"}; do
    [[ "$file" == "$skip" || "$file" == */"$skip" || "$(basename "$file")" == "$skip" ]] && return 0
  done
  return 1
}

files=()
for dir in "${dirs[@]}"; do
  [ -d "$dir" ] || { echo "check-function-size: not a directory: $dir" >&2; exit 2; }
  while IFS= read -r file; do
    excluded "$file" || files+=("$file")
  done < <(find "$dir" -name '*.cpp' -type f | sort)
done
((${#files[@]})) || { echo "check-function-size: no .cpp files in ${dirs[*]}" >&2; exit 2; }

# One row per function definition: file|name's line|closing brace's line|name.
tags=$("$ctags" -x --languages=C++ --kinds-C++=f --fields=+ne --_xformat='%F|%n|%e|%N' "${files[@]}") ||
  { echo "check-function-size: $ctags failed" >&2; exit 2; }
report=$(printf '%s\n' "$tags" | awk -F'|' -v threshold="$lines" '
  NF >= 4 && $3 != "" && $4 !~ /^__anon/ {  # a lambda counts within its function
    file = $1; start = $2 + 0; end = $3 + 0; name = $4
    if (!(file in loaded)) {
      n = 0
      while ((getline line < file) > 0) text[file, ++n] = line
      close(file)
      loaded[file] = 1
    }
    open = start
    while (open < end && index(text[file, open], "{") == 0) open++
    if (end - open > threshold)
      printf "%s:%d: function \x27%s\x27: %d lines (threshold %d)\n", file, start, name, end - open, threshold
  }' | sort -t: -k1,1 -k2,2n)
if [ -n "$report" ]; then
  echo "$report"
  echo "check-function-size: $(echo "$report" | wc -l) function(s) over $lines lines in ${#files[@]} file(s)"
  exit 1
fi
echo "check-function-size: no function over $lines lines in ${#files[@]} file(s)"
