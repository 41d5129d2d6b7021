#!/usr/bin/env bash
# A drum of rigid tetrahedra with friction, checkpointed and continued on 2 ranks: a body's
# spheres are placed by the rank owning the body, which need not be the rank their saved copies
# went to (this crashed the restore once). The continuation must run to its end and keep every
# particle.
# usage: rigid_restart_ranks.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
run() { "$mpirun" -q --allow-run-as-root --oversubscribe -np 2 "$exe" run "$@" >/dev/null; }
run rotating-drum --preset small --set equilibration_steps=0 --set steps=300 \
  --set progress_interval=0 --checkpoint-every 300 -o "$dir/first"
run --restart "$dir/first/checkpoint.h5" --set steps=400 --set checkpoint_every=0 -o "$dir/next"
/usr/bin/python3 - "$dir" <<'PY'
import json, sys
a = json.load(open(f"{sys.argv[1]}/first/summary.json"))
b = json.load(open(f"{sys.argv[1]}/next/summary.json"))
if a["N"] != b["N"]:
    print(f"FAIL: {a['N']} particles before the restart, {b['N']} after"); sys.exit(1)
print(f"ok: 2-rank drum continued from its checkpoint with all {b['N']} particles")
PY
