#!/usr/bin/env bash
# Runs a command that must fail: non-zero exit, exactly one line on stderr, matching a pattern.
# usage: expect_error.sh PATTERN COMMAND [ARGS...]
set -u
pattern=$1
shift
err=$(mktemp)
"$@" >/dev/null 2>"$err"
code=$?
lines=$(wc -l <"$err")
msg=$(cat "$err")
rm -f "$err"
if [ "$code" -eq 0 ]; then echo "FAIL: exit code 0 for: $*"; exit 1; fi
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines lines on stderr (want 1): $msg"; exit 1; fi
if ! grep -qE -- "$pattern" <<<"$msg"; then echo "FAIL: '$msg' does not match '$pattern'"; exit 1; fi
echo "ok (exit $code): $msg"
