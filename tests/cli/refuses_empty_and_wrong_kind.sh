#!/usr/bin/env bash
# Options given an empty value, or a thing of the wrong kind (a directory for a file, a binary
# file for an INI file, a truncated shared library for a plugin: the loader would die of SIGBUS
# in it), are refused at once: exit 2, one line naming the option or file.
# usage: refuses_empty_and_wrong_kind.sh EMERGENT
set -u
exe=$1
here=$(dirname "$0")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
head -c 2000 "$exe" >"$dir/binary.ini"
head -c 2000 "$exe" >"$dir/truncated.so"  # the executable is an ELF shared object too
fail=0
check() {  # PATTERN ARGS...
  "$here/expect_error.sh" "$@" || fail=1
}
run=(run capsid-assembly --preset tiny --set steps=5 --set progress_interval=0)
check "^emergent: error: --preset: the value is empty$" "$exe" run capsid-assembly --preset ""
check "^emergent: error: -o: the value is empty$" "$exe" "${run[@]}" -o ""
check "^emergent: error: --summary-json: the value is empty$" "$exe" "${run[@]}" --summary-json ""
check "^emergent: error: --restart: the value is empty$" "$exe" run --restart ""
check "--summary-json: '.*' is a directory, not a file name$" "$exe" "${run[@]}" --summary-json "$dir"
check "--restart: '.*' is not a file \(give the checkpoint.h5 itself\)$" "$exe" run --restart "$dir"
check "binary.ini:1: not a line of text \(control bytes\)" "$exe" "${run[@]}" --config "$dir/binary.ini"
check "^emergent: error: --plugin: the path is empty$" "$exe" --plugin "" list
check "cannot load plugin '.*truncated.so': a truncated or damaged shared library" "$exe" --plugin "$dir/truncated.so" list
check "^emergent: error: list takes no arguments, got 'extra'$" "$exe" list extra
check "^emergent: error: help takes one scene, got also 'extra'$" "$exe" help lj-fluid extra
# Nothing was written by any of them.
[ -z "$(ls "$dir" | grep -v '^binary.ini$' | grep -v '^truncated.so$')" ] || { echo "FAIL: files written: $(ls "$dir")"; fail=1; }
exit $fail
