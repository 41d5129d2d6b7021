#!/usr/bin/env bash
# Runs a command that must succeed: exit code 0 and its output matching a pattern (ctest's
# PASS_REGULAR_EXPRESSION alone ignores the exit code).
# usage: expect_output.sh PATTERN COMMAND [ARGS...]
set -u
pattern=$1
shift
out=$("$@" 2>&1)
code=$?
if [ "$code" -ne 0 ]; then echo "FAIL: exit code $code for: $*"; echo "$out"; exit 1; fi
if ! grep -qE -- "$pattern" <<<"$out"; then echo "FAIL: output does not match '$pattern':"; echo "$out"; exit 1; fi
echo "ok: $(grep -E -m1 -- "$pattern" <<<"$out")"
