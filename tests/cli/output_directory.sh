#!/usr/bin/env bash
# What -o DIR does with a directory that holds an earlier run (docs/running.md, "Output directory"):
# refused, nothing touched; --overwrite removes the earlier run's files (only those) before the
# new run writes; --restart continues beside them, replacing nothing whole; a failed run never
# leaves two runs mixed.
# usage: output_directory.sh EMERGENT EXPECT_ERROR MPIRUN
set -euo pipefail
exe=$1
expect_error=$2
mpirun=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
quiet=(--set progress_interval=0)
fingerprint() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum); }
fail() { echo "FAIL: $*"; exit 1; }

# An earlier run, with a user's own file beside it.
run=$work/run
"$exe" run lj-fluid --preset tiny "${quiet[@]}" --checkpoint-every 100 -o "$run" >/dev/null
echo "notes" >"$run/notes.txt"
before=$(fingerprint "$run")

# 1. A second run into it is refused, one line naming the directory and the ways on.
"$expect_error" "^emergent: error: -o $run: the directory holds an earlier run \(checkpoint.h5, .*\); give --overwrite to replace it, or continue it with --restart $run/checkpoint.h5, or choose another directory$" \
  "$exe" run lj-fluid --preset tiny -o "$run"
[ "$(fingerprint "$run")" = "$before" ] || fail "a refused run touched the directory"
# The same on two ranks: one line, exit 2.
"$expect_error" "^emergent: error: -o $run: the directory holds an earlier run" \
  "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run lj-fluid --preset tiny -o "$run"
[ "$(fingerprint "$run")" = "$before" ] || fail "a refused 2-rank run touched the directory"

# 2. --overwrite with input found bad only while the scene builds: nothing removed yet.
"$expect_error" "no particles" \
  "$exe" run taylor-couette --preset tiny --set density=1e-6 --overwrite -o "$run"
[ "$(fingerprint "$run")" = "$before" ] || fail "a refused --overwrite run touched the directory"

# 3. --overwrite replaces the earlier run: its checkpoint (which this run does not write) is
#    gone, the new run's files are the new scene's, the user's file stays.
"$exe" run granular-bed --preset tiny "${quiet[@]}" --overwrite -o "$run" >/dev/null
[ ! -e "$run/checkpoint.h5" ] || fail "--overwrite left the earlier run's checkpoint"
[ -f "$run/notes.txt" ] || fail "--overwrite removed a file the engine does not write"
grep -q '"scene": "granular-bed"' "$run/summary.json" || fail "summary is not the new run's"
/usr/bin/python3 - "$run/trajectory.h5" <<'PY' || fail "trajectory is not the new run's"
import sys, h5py
scene = h5py.File(sys.argv[1], "r")["parameters"].attrs["scene"]
assert (scene.decode() if isinstance(scene, bytes) else scene) == "granular-bed", scene
PY

# The summary alone says what was run: every resolved parameter, as the trajectory records
# them, and the build.
/usr/bin/python3 - "$run/summary.json" "$run/trajectory.h5" <<'PY' || fail "summary.json lacks what was run"
import json, sys, h5py
summary = json.load(open(sys.argv[1]))
recorded = h5py.File(sys.argv[2], "r")["parameters"].attrs
want = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in recorded.items()}
want.pop("scene")
assert summary["parameters"] == want, (summary["parameters"], want)
assert summary["parameters"]["nx"] and summary["build"]["git_commit"], summary["build"]
build = h5py.File(sys.argv[2], "r")["parameters/build"].attrs["git_commit"]
assert summary["build"]["git_commit"] == (build.decode() if isinstance(build, bytes) else build)
PY

# 4. A run that blows up (exit 3) into a directory holding a good run is refused before it
#    starts; in a directory of its own it leaves only its own files and its last good state.
good=$work/good
"$exe" run lj-fluid --preset tiny "${quiet[@]}" -o "$good" >/dev/null
kept=$(fingerprint "$good")
"$expect_error" "holds an earlier run" \
  "$exe" run lj-fluid --preset tiny --set dt=0.2 --set temperature=50 -o "$good"
[ "$(fingerprint "$good")" = "$kept" ] || fail "a refused unstable run touched the good run"
bad=$work/bad
"$expect_error" --code 3 "run stopped: .*the run went unstable" \
  "$exe" run lj-fluid --preset tiny --set dt=0.2 --set temperature=50 -o "$bad"
for f in "$bad"/*; do
  case $(basename "$f") in
    trajectory.h5|trajectory.xmf|snapshot.h5|last_good.h5) ;;
    *) fail "the failed run left $(basename "$f")" ;;
  esac
done

# 5. Continuing with --restart writes beside the earlier files and replaces none of them.
cont=$work/cont
"$exe" run lj-fluid --preset tiny "${quiet[@]}" --checkpoint-every 100 -o "$cont" >/dev/null
first=$(sha256sum "$cont/trajectory.h5")
step=$(/usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1],'r')['checkpoint'].attrs['step'])" "$cont/checkpoint.h5")
"$exe" run --restart "$cont/checkpoint.h5" --set steps=1000 --set checkpoint_every=0 "${quiet[@]}" >/dev/null
[ "$(sha256sum "$cont/trajectory.h5")" = "$first" ] || fail "a continuation changed trajectory.h5"
[ -f "$cont/trajectory.from$step.h5" ] || fail "no trajectory.from$step.h5"
# --overwrite would remove the checkpoint being continued: refused.
"$expect_error" "^emergent: error: --overwrite would remove the checkpoint this run continues from" \
  "$exe" run --restart "$cont/checkpoint.h5" --set steps=1000 --overwrite
# The continuation ran to its end without a newer checkpoint: continuing again from the same
# step would replace that whole segment, so it is refused.
segment=$(sha256sum "$cont/trajectory.from$step.h5")
"$expect_error" "'$cont/trajectory.from$step.h5' is a finished continuation from step $step" \
  "$exe" run --restart "$cont/checkpoint.h5" --set steps=1200
[ "$(sha256sum "$cont/trajectory.from$step.h5")" = "$segment" ] || fail "the finished segment changed"
# Into another directory it goes ahead.
"$exe" run --restart "$cont/checkpoint.h5" --set steps=1200 "${quiet[@]}" -o "$work/elsewhere" >/dev/null
[ -f "$work/elsewhere/trajectory.from$step.h5" ] || fail "no continuation in the other directory"

# 6. A continuation killed before it finished leaves an unfinished segment, which a retry
#    replaces (it was never whole).
killed=$work/killed
"$exe" run lj-fluid --preset tiny "${quiet[@]}" --checkpoint-every 100 -o "$killed" >/dev/null
step=$(/usr/bin/python3 -c "import h5py,sys; print(h5py.File(sys.argv[1],'r')['checkpoint'].attrs['step'])" "$killed/checkpoint.h5")
"$exe" run --restart "$killed/checkpoint.h5" --set steps=100000000 --set checkpoint_every=0 "${quiet[@]}" >/dev/null &
pid=$!
for _ in $(seq 100); do [ -f "$killed/trajectory.from$step.h5" ] && break; sleep 0.1; done
sleep 0.5
kill -9 $pid
wait $pid 2>/dev/null || true
"$exe" run --restart "$killed/checkpoint.h5" --set steps=1000 "${quiet[@]}" >/dev/null \
  || fail "the retry after a killed continuation was refused"

# 7. --overwrite needs a directory; -o naming a file is refused.
"$expect_error" "^emergent: error: --overwrite: no output directory given" \
  "$exe" run lj-fluid --preset tiny --overwrite
touch "$work/afile"
"$expect_error" "cannot create output directory '$work/afile'" \
  "$exe" run lj-fluid --preset tiny -o "$work/afile"
echo "ok: earlier runs refused, replaced only with --overwrite, continued without loss"
