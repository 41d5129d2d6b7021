#!/usr/bin/env bash
# Runs a command that must fail: the documented exit code, exactly one line on stderr, matching
# a pattern. Exit codes (docs/running.md, "Exit codes"): 2 bad input (the default here), 3 run-time fault,
# 4 I/O failure.
# usage: expect_error.sh [--code N] PATTERN COMMAND [ARGS...]
set -u
want=2
if [ "$1" = "--code" ]; then want=$2; shift 2; fi
pattern=$1
shift
err=$(mktemp)
"$@" >/dev/null 2>"$err"
code=$?
lines=$(wc -l <"$err")
msg=$(cat "$err")
rm -f "$err"
if [ "$code" -ne "$want" ]; then echo "FAIL: exit code $code (want $want) for: $*: $msg"; exit 1; fi
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines lines on stderr (want 1): $msg"; exit 1; fi
if ! grep -qE -- "$pattern" <<<"$msg"; then echo "FAIL: '$msg' does not match '$pattern'"; exit 1; fi
echo "ok (exit $code): $msg"
