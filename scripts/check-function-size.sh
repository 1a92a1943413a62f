#!/usr/bin/env bash
# Functions longer than a line threshold (clang-tidy's readability-function-size,
# LineThreshold: the body's lines, blank and comment lines included) in the .cpp
# files of the given directories, each compiled as the build directory's
# compile_commands.json says. Prints every offender as
#   path:line: function 'name': N lines (threshold T)
# and exits 1 if there is one, 0 if none, 2 on bad use.
#   bash scripts/check-function-size.sh [--build DIR] [--lines N] [--exclude FILE]... DIR...
# (defaults: --build build, --lines 60; --exclude leaves out one file, by its
# path as given or its name, and may be repeated; CLANG_TIDY names the program,
# default clang-tidy; JOBS clang-tidy processes at once, default 2).
set -euo pipefail
usage() { echo "usage: check-function-size.sh [--build DIR] [--lines N] [--exclude FILE]... DIR..." >&2; exit 2; }
build=build
lines=60
excludes=()
dirs=()
while (($#)); do
  case "$1" in
    --build) (($# >= 2)) || usage; build=$2; shift 2 ;;
    --lines) (($# >= 2)) || usage; lines=$2; shift 2 ;;
    --exclude) (($# >= 2)) || usage; excludes+=("$2"); shift 2 ;;
    -*) usage ;;
    *) dirs+=("$1"); shift ;;
  esac
done
((${#dirs[@]})) || usage
[[ "$lines" =~ ^[1-9][0-9]*$ ]] || { echo "check-function-size: --lines must be a positive integer, got '$lines'" >&2; exit 2; }
tidy=${CLANG_TIDY:-clang-tidy}
command -v "$tidy" >/dev/null || { echo "check-function-size: $tidy not found" >&2; exit 2; }
[ -f "$build/compile_commands.json" ] ||
  { echo "check-function-size: no $build/compile_commands.json (configure with CMAKE_EXPORT_COMPILE_COMMANDS)" >&2; exit 2; }

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

config="{CheckOptions: [{key: readability-function-size.LineThreshold, value: $lines}]}"
# One clang-tidy per file, each into its own file so that parallel runs do not
# interleave; it reports an offender as a warning naming the function, then a
# note with its line count, joined here into one line.
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export tidy build config out
printf '%s\0' "${files[@]}" |
  xargs -0 -n 1 -P "${JOBS:-2}" bash -c \
    '"$tidy" -p "$build" --quiet --checks="-*,readability-function-size" --config="$config" "$0" \
       > "$out/$(printf %s "$0" | tr / _).txt" 2>/dev/null || printf "%s\n" "$0" >> "$out/failed"'
if [ -f "$out/failed" ]; then
  sed 's/^/check-function-size: clang-tidy failed on /' "$out/failed" >&2
  exit 2
fi
report=$(cat "$out"/*.txt | awk -v threshold="$lines" '
    /warning: function .* exceeds recommended size\/complexity thresholds/ {
      split($0, at, ":"); where = at[1] ":" at[2]
      name = $0; sub(/^[^\x27]*\x27/, "", name); sub(/\x27.*$/, "", name)
      next
    }
    where != "" && / note: [0-9]+ lines including whitespace and comments/ {
      count = $0; sub(/^.* note: /, "", count); sub(/ lines.*$/, "", count)
      printf "%s: function \x27%s\x27: %d lines (threshold %d)\n", where, name, count, threshold
      where = ""
    }' | sort -t: -k1,1 -k2,2n)
if [ -n "$report" ]; then
  echo "$report"
  echo "check-function-size: $(echo "$report" | wc -l) function(s) over $lines lines in ${#files[@]} file(s)"
  exit 1
fi
echo "check-function-size: no function over $lines lines in ${#files[@]} file(s)"
