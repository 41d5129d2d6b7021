#!/usr/bin/env bash
# The figure scripts read a run's files and write PNG images.
# usage: figure_scripts.sh EMERGENT SCRIPTS_DIR
set -euo pipefail
exe=$1
scripts=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$exe" run lj-fluid --preset tiny --set fields.interval=100 --set fields.grid=4x1x6 \
  --set progress_interval=0 -o "$dir" >/dev/null
"$scripts/plot_observables" "$dir" "$dir/obs.png" >/dev/null
"$scripts/plot_field_slice" "$dir" box density "$dir/rho.png" >/dev/null
"$exe" run taylor-couette --preset tiny --set steps=1000 --set fields.interval=250 \
  --set progress_interval=0 -o "$dir/tc" >/dev/null
"$scripts/plot_taylor_couette" "$dir/tc" "$dir/tc/fig" >/dev/null
"$exe" run rayleigh-benard --preset tiny --set steps=1000 --set fields.interval=250 \
  --set fields.grid=4x4x5 --set progress_interval=0 -o "$dir/rb" >/dev/null
"$scripts/plot_rayleigh_benard" "$dir/rb" "$dir/rb/fig" >/dev/null
# A run continued from its checkpoint is read as one run by the comparison script: frames
# every 1.25 tau to 7.5 (1500 steps), each once and in order, each with its Nusselt number.
"$exe" run rayleigh-benard --preset tiny --set steps=1000 --set fields.interval=250 \
  --set conduction_flux=0.5 --set progress_interval=0 --checkpoint-every 500 -o "$dir/rbc" >/dev/null
"$exe" run --restart "$dir/rbc/checkpoint.h5" --set steps=1500 --set progress_interval=0 \
  -o "$dir/rbc" >/dev/null
"$exe" run rayleigh-benard --preset tiny --set steps=500 --set fields.interval=250 \
  --set noise_amplitude=0.1 --set progress_interval=0 -o "$dir/rbn" >/dev/null
"$scripts/compare_rayleigh_benard" "$dir/cmp" "$dir/rbc=continued" "$dir/rbn=seeded" >"$dir/cmp.txt"
/usr/bin/python3 - "$dir/cmp.txt" <<'PY'
import sys
rows = [l.split("|")[1:-1] for l in open(sys.argv[1]) if l.startswith("| ") and "t (tau)" not in l]
continued = rows[:6]
times = [float(r[0]) for r in continued]
assert times == [1.25 * k for k in range(1, 7)], times
assert all(r[2].strip() != "-" for r in continued), continued
assert len(rows) == 6 + 2, rows
PY
# The seeds' figure is drawn from such tables alone (the continued run's: 6 frames, the last
# quarter its last 1.5 of them, so frames 5 and 6 after rounding down): its printed quarter
# mean is that of the table's Nusselt numbers there.
"$scripts/plot_rayleigh_benard_seeds" "$dir/seeds.png" "$dir/cmp.txt=continued" >"$dir/seeds.txt"
[ -s "$dir/seeds.png" ] || { echo "FAIL: plot_rayleigh_benard_seeds wrote no figure"; exit 1; }
/usr/bin/python3 - "$dir/cmp.txt" "$dir/seeds.txt" <<'PY'
import re, sys
rows = [l.split("|")[1:-1] for l in open(sys.argv[1]) if l.startswith("| ") and "t (tau)" not in l][:6]
nu = [float(r[2]) for r in rows]
printed = open(sys.argv[2]).read()
got = float(re.search(r"last quarter \(2 frames\): Nu ([0-9.]+)", printed).group(1))
assert abs(got - (nu[4] + nu[5]) / 2) < 6e-4, (got, nu, printed)
PY
if "$scripts/plot_rayleigh_benard_seeds" "$dir/none.png" "$dir/rb/summary.json" >/dev/null 2>&1; then
  echo "FAIL: plot_rayleigh_benard_seeds took a file without a frame table"; exit 1
fi
"$exe" run rotating-drum --preset tiny --set progress_interval=0 -o "$dir/rd" >/dev/null
"$scripts/plot_rotating_drum" "$dir/rd" "$dir/rd/fig" >/dev/null
"$exe" run vibrated-sawtooth --preset tiny --set steps=5000 --set sample_every=250 \
  --set slot_ends=walls --set output.every=2500 --set progress_interval=0 -o "$dir/vs" >/dev/null
"$scripts/plot_vibrated_sawtooth" "$dir/vs" "$dir/vs/fig" >/dev/null
"$exe" run vibrated-sawtooth --preset tiny --set steps=5000 --set sample_every=250 \
  --set slot_ends=walls --set seed=2 --set progress_interval=0 -o "$dir/vs2" >/dev/null
"$scripts/plot_sawtooth_seeds" "$dir/vs/seeds.png" "$dir/vs" "$dir/vs2" >/dev/null
# capsid-assembly's mass fractions: the closed shell at e = 0.09 is all in the group of 60 (the
# note's site rows, whose numbers the contacts below are checked against).
"$exe" run capsid-assembly --preset tiny --set attraction=0.09 --set site_depth_outer=0.5 --set steps=400 --set sample_every=100 \
  --set output.every=100 --set progress_interval=0 --checkpoint-every 400 -o "$dir/cs" >/dev/null
"$scripts/plot_capsid_mass_fractions" "$dir/cs/mass.png" "$dir/cs" >"$dir/cs/mass.txt"
grep -q "60 1.000$" "$dir/cs/mass.txt" || { echo "FAIL: the shell's mass fractions: $(cat "$dir/cs/mass.txt")"; exit 1; }
# The long runs' table: the shell holds all the mass from the first sample on (step 100, 0.5 tau).
"$scripts/../benchmarks/capsid_assembly_long.sh" table "$dir/cs" >"$dir/cs/table.txt"
grep -q "^# mass in complete shells at the end: 1.000; half of it first at 0.5 tau$" "$dir/cs/table.txt" \
  || { echo "FAIL: capsid_assembly_long.sh table: $(cat "$dir/cs/table.txt")"; exit 1; }
# Its shape: one closed cage of 60 on a sphere of the design's centre radius |c| = 4.215747
# (notes/capsid-geometry.md); thermal motion over 400 steps moves the fit by far less than 1 %.
"$scripts/capsid_cages" "$dir/cs" >"$dir/cs/cages.txt"
awk -F'|' '$2 + 0 == 60 && $6 ~ /yes/ && ($3 - 4.215747) ^ 2 < 0.04 ^ 2 {found = 1} END {exit !found}' \
  "$dir/cs/cages.txt" || { echo "FAIL: the shell's cage: $(cat "$dir/cs/cages.txt")"; exit 1; }
for bad in "$dir/none" "$dir/cs x" "$dir/cs 6 99"; do  # bad input: one line, status 1
  rc=0; err=$("$scripts/capsid_cages" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_cages $bad: status $rc, $err"; exit 1; }
done
# The shell drawn whole, monomers hidden: one cluster of 60 with 5 bonds per member, its members'
# centres (means of their spheres) at the design's centre radius within the cages' 1 %.
"$scripts/plot_capsid_clusters" "$dir/cs/clusters.png" "$dir/cs" >"$dir/cs/clusters.txt"
awk -F'|' 'NF > 3 && $2 + 0 > 0 {rows++; if ($2 + 0 == 60 && $3 + 0 == 5 && ($4 - 4.215747) ^ 2 < 0.04 ^ 2) found = 1}
  END {exit !(found && rows == 1)}' "$dir/cs/clusters.txt" \
  || { echo "FAIL: the shell drawn: $(cat "$dir/cs/clusters.txt")"; exit 1; }
for bad in "$dir/none" "$dir/cs x" "$dir/cs 99"; do  # bad input: one line, status 1
  rc=0; err=$("$scripts/plot_capsid_clusters" "$dir/cs/bad.png" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: plot_capsid_clusters $bad: status $rc, $err"; exit 1; }
done
# Each member of the shell predicts the same shell centre: exactly at the start; after 2 tau at
# e = 0.09 every member within 1.5 of it and most within 0.5 (perfect patches at e = 0.1225 keep
# ~75 % within 0.5, benchmarks/logs/capsid_shell_register_2026-12-05.log).
"$scripts/capsid_shell_register" "$dir/cs" "$dir/cs" 6 0 -1 >"$dir/cs/register.txt"
grep -q "^| 0 | 60 | 5.00 | 60 | 0 | 0 | 4.22 |$" "$dir/cs/register.txt" \
  || { echo "FAIL: the shell's register at the start: $(cat "$dir/cs/register.txt")"; exit 1; }
awk -F'|' '$2 + 0 == 400 && $3 + 0 == 60 && $5 + 0 >= 30 && $5 + $6 == 60 && $7 + 0 == 0 {found = 1} END {exit !found}' \
  "$dir/cs/register.txt" || { echo "FAIL: the shell's register at step 400: $(cat "$dir/cs/register.txt")"; exit 1; }
# Small clusters from monomers at a strong attraction, a frame at every sample: the script's mean
# number of dimers and of monomers over the frames are the engine's measures at those steps.
"$exe" run capsid-assembly --preset tiny --set start=monomers --set solvent=implicit --set attraction=0.3 \
  --set dt=0.02 --set steps=10000 --set sample_every=250 --set output.every=250 --set progress_interval=0 \
  -o "$dir/cm" >/dev/null
"$scripts/capsid_small_clusters" "$dir/cm" 2 >"$dir/cm/small.txt"
# Table 1 at equal run length (benchmarks/capsid_assembly_long.sh at): samples every 5 tau, so at
# 102 tau the row is the sample at 100, its fractions sum to 1, and plot_capsid_table1 reads the
# same row back; a run that has not reached the time is named and the status is 3.
long="$scripts/../benchmarks/capsid_assembly_long.sh"
"$long" at 102 "$dir/cm" >"$dir/cm/at.txt"
awk -F'|' '$2 + 0 == 0.3 && $4 + 0 == 100 {s = $5 + $6 + $7 + $8 + $9; if (s > 0.9995 && s < 1.0005) found = 1}
  END {exit !found}' "$dir/cm/at.txt" || { echo "FAIL: capsid_assembly_long.sh at 102: $(cat "$dir/cm/at.txt")"; exit 1; }
monomers=$(awk -F'|' '$2 + 0 == 0.3 {printf "%.3f", $5}' "$dir/cm/at.txt")
"$scripts/plot_capsid_table1" "$dir/cm/table1.png" "$dir/cm/at.txt" >"$dir/cm/table1.txt"
grep -q "^e 0.3, 102 tau, 1 seed(s): 1 $monomers, " "$dir/cm/table1.txt" \
  || { echo "FAIL: plot_capsid_table1 on the at table: $(cat "$dir/cm/table1.txt")"; exit 1; }
rc=0; "$long" at 1000 "$dir/cm" >"$dir/cm/at_short.txt" || rc=$?
[ $rc = 3 ] && grep -q "^# not reached: $dir/cm (to 200 tau)$" "$dir/cm/at_short.txt" \
  || { echo "FAIL: capsid_assembly_long.sh at 1000: status $rc, $(cat "$dir/cm/at_short.txt")"; exit 1; }
rc=0; err=$("$long" at x "$dir/cm" 2>&1 >/dev/null) || rc=$?
[ $rc = 2 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_assembly_long.sh at x: status $rc, $err"; exit 1; }
# Contacts, apart from the engine's census: the closed shell at the start has the note's 150 bonds
# of four matched pairs, no partial contact, and the note's site attraction -1272.56 at e = 0.09
# (notes/capsid-geometry.md 3.7); in the monomer run's last frame, a face pair with all four
# pairs within r_b is exactly a census bond (as many as the frame's bonds per capsomer say, and
# none between two census clusters).
"$scripts/capsid_contacts" "$dir/cs" 0 >"$dir/cs/contacts.txt"
grep -q "^| within census clusters | 0 | 0 | 0 | 150 |$" "$dir/cs/contacts.txt" \
  && grep -q "^| between census clusters | 0 | 0 | 0 | 0 |$" "$dir/cs/contacts.txt" \
  && grep -q "^site attraction (kT): within census clusters -1272.6, " "$dir/cs/contacts.txt" \
  || { echo "FAIL: the shell's contacts: $(cat "$dir/cs/contacts.txt")"; exit 1; }
"$scripts/capsid_contacts" "$dir/cm" >"$dir/cm/contacts.txt"
/usr/bin/python3 - "$dir/cm" "$scripts" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
from emergentpy import Run
text = open(f"{sys.argv[1]}/contacts.txt").read()
rows = {l.split("|")[1].strip(): [int(v) for v in l.split("|")[2:6]] for l in text.splitlines() if "census clusters |" in l}
bonds = int(Run(sys.argv[1]).body_frames()[3][-1].sum()) // 2
assert rows["within census clusters"][3] == bonds and bonds > 0, (rows, bonds)
assert rows["between census clusters"][3] == 0, rows
PY
/usr/bin/python3 - "$dir/cm" "$scripts" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
import numpy as np
from emergentpy import Run
lines = open(f"{sys.argv[1]}/small.txt").read().splitlines()
frames = int(lines[0].split(": ")[1].split()[0])
dimers = [float(l.split("|")[2]) for l in lines if l.startswith("| 2 |")][0]
monomers = float([l for l in lines if l.startswith("mass fractions")][0].split()[6].rstrip(","))
_, engine_dimers = Run(sys.argv[1]).observable("dimers")
_, mass = Run(sys.argv[1]).observable("mass_fractions")
# The frames add step 0 (60 monomers, no dimers) to the samples; the script rounds to 2 and 3 decimals.
assert frames == len(engine_dimers) + 1, (frames, len(engine_dimers))
assert abs(dimers * frames - np.sum(engine_dimers)) < 0.005 * frames + 1e-9, (dimers, np.sum(engine_dimers))
assert abs(monomers * frames - (np.asarray(mass)[:, 0].sum() + 1)) < 0.0005 * frames + 1e-9, (monomers, mass)
assert np.sum(engine_dimers) > 0, "no dimers formed to compare"
PY
for bad in "$dir/none $dir/cs" "$dir/cs $dir/cm" "$dir/cs $dir/cs x" "$dir/cs $dir/cs 6 99"; do  # one line, status 1
  rc=0; err=$("$scripts/capsid_shell_register" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_shell_register $bad: status $rc, $err"; exit 1; }
done
# Openings: the open 59-cluster has one empty place, predicted by its 5 neighbours, exactly where
# the closed shell's member sits that the `open_shell` start leaves out (both starts place the
# same shell; step 0, so no motion yet); the closed shell has none. Then that frame with the
# freed capsomer moved 2 out over the opening: a monomer over it, not capped; and with the same
# capsomer labelled a member of a cluster of 6: capped by it.
"$exe" run capsid-assembly --preset tiny --set start=open_shell --set attraction=0.09 --set site_depth_outer=0.5 \
  --set steps=100 --set sample_every=100 --set output.every=100 --set progress_interval=0 -o "$dir/co" >/dev/null
"$scripts/capsid_holes" "$dir/cs" "$dir/cs" 51 0 >"$dir/cs/holes.txt"
grep -q "^# openings: 0 open, 0 capped by a cluster of 6+ (0.0 by chance" "$dir/cs/holes.txt" \
  || { echo "FAIL: the closed shell's openings: $(cat "$dir/cs/holes.txt")"; exit 1; }
"$scripts/capsid_holes" "$dir/co" "$dir/cs" 51 0 >"$dir/co/holes.txt"
/usr/bin/python3 - "$dir" "$scripts" <<'PY'
import shutil, subprocess, sys
sys.path.insert(0, sys.argv[2])
import h5py
import numpy as np
from emergentpy import Run
d, scripts = sys.argv[1], sys.argv[2]
def rows(text):
    return [[c.strip() for c in l.split("|")[1:-1]] for l in text.splitlines() if l.startswith("| ") and "t (tau)" not in l]
(row,) = rows(open(f"{d}/co/holes.txt").read())
assert row[2:6] == ["59", "1 of 1", "1", "5"] and row[7:] == ["0", "0", "-", "no", "0.00"], row
shell = Run(f"{d}/cs").body_frames()[4][0]
_, _, size, _, x, lengths = Run(f"{d}/co").body_frames()
lengths = np.diag(lengths) if np.ndim(lengths) == 2 else lengths
def gap(a, b):
    r = a - b
    return np.linalg.norm(r - lengths * np.round(r / lengths), axis=-1)
missing = shell[np.argmax([gap(p, x[0][size[0] == 59]).min() for p in shell])]
at = np.array(row[6].split(), float)
assert gap(at, missing) < 0.05, (at, missing)
# The freed capsomer moved 2 out over the opening (outward from the shell's centre).
shutil.copytree(f"{d}/co", f"{d}/cc")
path = Run(f"{d}/cc").trajectory_paths[0]
with h5py.File(path, "r+") as f:
    fr = f["particles/bodies/frames"]
    free = int(np.flatnonzero(fr["cluster_size/000000"][:] == 1)[0])
    rel = shell - shell[0]
    out = at - (shell[0] + (rel - lengths * np.round(rel / lengths)).mean(0))
    fr["position/000000"][free] = at + 2.0 * out / np.linalg.norm(out)
def holes():
    return rows(subprocess.run([f"{scripts}/capsid_holes", f"{d}/cc", f"{d}/cs", "51", "0"], check=True,
                               capture_output=True, text=True).stdout)
(row,) = holes()
assert row[7:] == ["1", "0", "-", "no", "0.00"], row
with h5py.File(path, "r+") as f:
    f["particles/bodies/frames/cluster_size/000000"][free] = 6
# Capped, and the capsomer's 2.5 reach a small share of the cluster's sphere of radius 4.2.
(row,) = holes()
assert row[7:11] == ["0", "0", "6", "yes"] and 0 < float(row[11]) < 0.1, row
PY
for bad in "$dir/none $dir/cs" "$dir/cs $dir/co" "$dir/cs $dir/cs x" "$dir/cs $dir/cs 60" "$dir/cs $dir/cs 51 99"; do
  rc=0; err=$("$scripts/capsid_holes" $bad 2>&1 >/dev/null) || rc=$?  # one line, status 1
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_holes $bad: status $rc, $err"; exit 1; }
done
# A seeded dimer with no attraction: its census ends once, and the two capsomers drift apart
# (no force holds them; relative diffusion takes them 3 beyond contact in a few tau, inside the
# 20 tau window) before any bond forms again.
"$exe" run capsid-assembly --preset tiny --set start=cluster --set cluster_size=2 --set solvent=implicit \
  --set attraction=0 --set dt=0.02 --set steps=2500 --set sample_every=25 --set output.every=25 \
  --set progress_interval=0 -o "$dir/cd" >/dev/null
"$scripts/capsid_small_clusters" "$dir/cd" 2 20 >"$dir/cd/small.txt"
grep -q "not by growth (windows of 20 tau = 40 frames inside the run): 1; bonded again first 0, centres beyond [0-9.]* first 1, neither 0$" \
  "$dir/cd/small.txt" || { echo "FAIL: the seeded dimer's end: $(tail -1 "$dir/cd/small.txt")"; exit 1; }
# The other branch: at e = 0.2 a bonded pair sits deep in its well (at 0.1225 already 2 in 3 census
# ends are flickers, benchmarks/logs/capsid_dimer_census_ends_2026-12-05.log), so the census ends
# when a site pair strays past r_b and the pair is bonded again within a few frames; the three
# outcomes must add up to the ends counted.
"$exe" run capsid-assembly --preset tiny --set start=cluster --set cluster_size=2 --set solvent=implicit \
  --set attraction=0.2 --set dt=0.02 --set steps=2500 --set sample_every=25 --set output.every=25 \
  --set progress_interval=0 -o "$dir/cb" >/dev/null
"$scripts/capsid_small_clusters" "$dir/cb" 2 20 >"$dir/cb/small.txt"
/usr/bin/python3 - "$dir/cb/small.txt" <<'PY'
import re, sys
last = open(sys.argv[1]).read().splitlines()[-1]
m = re.search(r"inside the run\): (\d+); bonded again first (\d+)\b.*first (\d+), neither (\d+)$", last)
assert m, last
ended, again, apart, neither = map(int, m.groups())
assert ended == again + apart + neither, last
assert again >= 1 and again >= apart, last
PY
for bad in "$dir/none" "$dir/cm x" "$dir/cm 2 0" "$dir/cm 2 x"; do
  rc=0; err=$("$scripts/capsid_small_clusters" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_small_clusters $bad: status $rc, $err"; exit 1; }
done
for bad in "$dir/none" "$dir/cm x" "$dir/cm 99" "$dir/cm 0 1"; do
  rc=0; err=$("$scripts/capsid_contacts" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_contacts $bad: status $rc, $err"; exit 1; }
done
# Where new clusters come from, on body frames written here with a known history (10 capsomers
# 1.5 apart on a line, clusters of 3+ counted, frames 0.5 tau apart): 0-4 are one cluster; 5 and
# 6 meet as monomers at frame 2 and 7 joins them at 3 (new, from monomers); 3 and 4 leave the
# cluster of 5 together at frame 4, after 4 frames together in it, and 8 joins them at 5 (new,
# from a piece); at 6 all but 5-6-7 merge (not new) and at 7 the merger sheds 3-4-8 (new, a piece
# of 3 of 7 at once) while 0-1-2-9 go on (not new); at 8 5-6-7 loses 7 and at 9 takes it back
# (the same cluster back above 3: not new, counted apart).
mkdir -p "$dir/no"
/usr/bin/python3 - "$dir/no/trajectory.h5" <<'PY'
import sys
import h5py, numpy as np
frames = [
    [0, 0, 0, 0, 0, 5, 6, 7, 8, 9],
    [0, 0, 0, 0, 0, 5, 6, 7, 8, 9],
    [0, 0, 0, 0, 0, 5, 5, 7, 8, 9],
    [0, 0, 0, 0, 0, 5, 5, 5, 8, 9],
    [0, 0, 0, 3, 3, 5, 5, 5, 8, 9],
    [0, 0, 0, 3, 3, 5, 5, 5, 3, 9],
    [0, 0, 0, 0, 0, 5, 5, 5, 0, 0],
    [0, 0, 0, 3, 3, 5, 5, 5, 3, 0],
    [0, 0, 0, 3, 3, 5, 5, 7, 3, 0],
    [0, 0, 0, 3, 3, 5, 5, 5, 3, 0],
]
with h5py.File(sys.argv[1], "w") as f:
    g = f.create_group("particles/bodies")
    g["box/edges/value"] = np.array([[20.0, 20.0, 20.0]])
    g["cluster/step"] = np.arange(len(frames)) * 100
    g["cluster/time"] = np.arange(len(frames)) * 0.5
    g["bonds/step"] = np.arange(len(frames)) * 100
    for k, c in enumerate(frames):
        c = np.array(c)
        name = f"{k:06d}"
        g[f"frames/cluster/{name}"] = c
        g[f"frames/cluster_size/{name}"] = np.array([np.sum(c == v) for v in c])
        g[f"frames/bonds/{name}"] = np.zeros(len(c), int)
        g[f"frames/id/{name}"] = np.arange(len(c))
        g[f"frames/position/{name}"] = np.array([[1.5 * b, 0.0, 0.0] for b in range(len(c))])
PY
"$scripts/capsid_nucleus_origin" "$dir/no" 3 >"$dir/no/origin.txt"
grep -q "^| 1.5 | 3 | monomers | 1 |  | 1.5 (0.00) | 3 |$" "$dir/no/origin.txt" \
  && grep -q "^| 2.5 | 3 | piece | 2 | 2 of 5, 4 | 1.5 (0.50) | 3 |$" "$dir/no/origin.txt" \
  && grep -q "^| 3.5 | 3 | piece | 3.5 | 3 of 7 | 1.5 (-) | 3 |$" "$dir/no/origin.txt" \
  && grep -q "^new clusters of 3+: 3; from pieces 2, from monomers 1, there at the start 0; not counted: clusters back above 3 after dropping below it 1$" "$dir/no/origin.txt" \
  || { echo "FAIL: capsid_nucleus_origin on a known history: $(cat "$dir/no/origin.txt")"; exit 1; }
for bad in "$dir/none" "$dir/no x" "$dir/no 2"; do
  rc=0; err=$("$scripts/capsid_nucleus_origin" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_nucleus_origin $bad: status $rc, $err"; exit 1; }
done
# The PW capsomer's closed cages, apart from the engine: its log's numbers, which the engine's
# closed_cage() is compared with in physics_capsomer (benchmarks/logs/capsid_polymorphs_2026-12-04.log).
"$scripts/capsid_polymorphs" >"$dir/cs/polymorphs.txt"
grep -q "^| 24 | -19.3189 | 0.2807 | 1.9499 | 2.6372 | 5 | 0.196 |$" "$dir/cs/polymorphs.txt" \
  || { echo "FAIL: the 24-cage: $(cat "$dir/cs/polymorphs.txt")"; exit 1; }
for bad in "1.3 1.2" "x 1" "0 1 2 3"; do  # bad input: one line, status 1
  rc=0; err=$("$scripts/capsid_polymorphs" $bad 2>&1 >/dev/null) || rc=$?
  [ $rc = 1 ] && [ "$(wc -l <<<"$err")" = 1 ] || { echo "FAIL: capsid_polymorphs $bad: status $rc, $err"; exit 1; }
done
# Table 1 beside ours, from a committed log: e = 0.15 averages its two seeds' rows (monomers
# 0.370 and 0.447; 2-5 plus 6-50: 0.630 and 0.553).
"$scripts/plot_capsid_table1" "$dir/cs/table1.png" "$scripts/../benchmarks/logs/capsid_table1_2026-12-03.log" >"$dir/cs/table1.txt"
grep -q "^e 0.15, 0.4e6 steps, 2 seed(s): 1 0.408, 2-50 0.592, 51-59 0.000, 60 0.000$" "$dir/cs/table1.txt" \
  || { echo "FAIL: Table 1's averages: $(cat "$dir/cs/table1.txt")"; exit 1; }
for png in "$dir/cs/mass.png" "$dir/cs/table1.png" "$dir/cm/table1.png" "$dir/cs/clusters.png" "$dir/vs/fig-spacetime.png" "$dir/vs/fig-profile.png" "$dir/vs/fig-views.png" "$dir/vs/seeds.png" \
           "$dir/rd/fig-spacetime.png" "$dir/rd/fig-segregation.png" "$dir/rd/fig-snapshot.png" \
           "$dir/obs.png" "$dir/rho.png" "$dir/tc/fig-rolls.png" "$dir/tc/fig-radial-velocity.png" \
           "$dir/tc/fig-vortices.png" "$dir/rb/fig-cells.png" "$dir/rb/fig-cell-count.png" \
           "$dir/rb/fig-flow.png" "$dir/cmp.png"; do
  # A PNG signature and more than a blank canvas's worth of bytes.
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] || { echo "FAIL: $png is not a PNG"; exit 1; }
  [ "$(stat -c %s "$png")" -gt 10000 ] || { echo "FAIL: $png is nearly empty"; exit 1; }
done
# The GPU work-precision diagram from the measured table kept in benchmarks/logs.
"$scripts/plot_gpu_work_precision" "$scripts/../benchmarks/logs/gpu_work_precision_h100.csv" \
  "$dir/gpu_wp.png" >/dev/null
[ "$(stat -c %s "$dir/gpu_wp.png")" -gt 10000 ] || { echo "FAIL: gpu_wp.png is nearly empty"; exit 1; }
/usr/bin/python3 - "$dir" "$scripts" <<'PY'
import sys
sys.path.insert(0, sys.argv[2])
from emergentpy import Run
run = Run(sys.argv[1])
assert run.complete()
assert run.parameters()["scene"] == "lj-fluid"
step, x = run.frame("position", -1)
assert step == 400 and x.shape == (256, 3)
t, rho = run.field("box", "density")
assert rho.shape == (4, 6, 1, 4), rho.shape
# A continued run reads as one: series and fields joined in time, each time once.
both = Run(sys.argv[1] + "/rbc")
assert len(both.segments()) == 2, both.segments()
t, T = both.observable("temperature")
assert (t[1:] > t[:-1]).all() and len(t) == 15 and abs(t[-1] - 7.5) < 1e-9, t  # every 0.5 tau
tf, slice_t = both.field("slice", "temperature")
assert len(tf) == 6 and abs(tf[-1] - 7.5) < 1e-9, tf
assert both.parameters()["steps"] == "1500"
step, _ = both.frame("position", -1)
assert step == 1500, step
print("ok: figure scripts wrote PNGs; emergentpy reads the run and a continued one")
PY
