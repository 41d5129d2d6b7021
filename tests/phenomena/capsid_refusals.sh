#!/usr/bin/env bash
# scripts/check_phenomenon on capsid-assembly runs it cannot judge: an open-cluster start (the
# open side of the hysteresis is a comparison over seeds) and a shell at e = 0.09, where
# clusters grow and a holding shell shows no hysteresis. Each is one line on stderr, exit 2.
# usage: capsid_refusals.sh EMERGENT
set -euo pipefail
exe=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
refused() {  # NAME EXPECTED-TEXT SETTINGS...
  local name=$1 text=$2 rc=0 err
  shift 2
  "$exe" run capsid-assembly --preset tiny --set steps=200 --set progress_interval=0 "$@" -o "$dir/$name" >/dev/null
  err=$("$root/scripts/check_phenomenon" "$dir/$name" 2>&1 >/dev/null) || rc=$?
  [ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] && [[ "$err" == *"$text"* ]] ||
    { echo "FAIL: $name: status $rc, '$err'"; exit 1; }
  echo "ok: $name refused: $err"
}
refused open_start "not start=open_shell" --set start=open_shell --set capsomers=80 --set attraction=0.062
refused growth_range "attraction=0.09 is not below 0.09" --set attraction=0.09
