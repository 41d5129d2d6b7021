#!/usr/bin/env bash
# Every program in scripts/ answers --help and -h with its usage on stdout and exit status 0,
# having done nothing else (run from an empty folder, it leaves it empty; a build or an install
# would take far longer than the limit here).
# usage: scripts_help.sh SCRIPTS_DIR
set -uo pipefail
scripts=$(cd "$1" && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
cd "$dir"
failed=0 checked=0
for f in "$scripts"/*; do
  [ -f "$f" ] && [ -x "$f" ] || continue
  for flag in --help -h; do
    out=$(timeout 30 "$f" "$flag" 2>"$dir.err")
    rc=$?
    checked=$((checked + 1))
    if [ $rc -ne 0 ] || ! grep -qi '^ *usage' <<<"$out"; then
      echo "FAIL: $(basename "$f") $flag: exit $rc, $(grep -ci usage <<<"$out") usage lines; stderr: $(head -c 300 "$dir.err")"
      failed=1
    fi
    if [ -n "$(ls -A "$dir")" ]; then
      echo "FAIL: $(basename "$f") $flag wrote $(ls -A "$dir" | head -3 | paste -sd' ')"
      rm -rf "${dir:?}"/* "$dir"/.[!.]* 2>/dev/null
      failed=1
    fi
  done
done
rm -f "$dir.err"
[ $checked -ge 20 ] || { echo "FAIL: only $checked answers checked"; exit 1; }
echo "scripts_help: $checked answers checked"
exit $failed
