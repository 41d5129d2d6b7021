#!/usr/bin/env bash
# capsid-assembly at `tiny` (60 capsomers in explicit solvent), with seeds other than the preset's:
#   a closed shell at e = 0.09 stays one complete shell (60 members, 150 bonds, every degree 5)
#   at every sample of 4000 steps, on 2 ranks (the shell straddles the domain boundary, so the
#   census gathers sites across ranks);
#   so does the closed shell of the alternative PH design (shape=ph), on 1 rank;
#   the same shell with no attraction falls apart: no cluster larger than 5 at the end;
#   without attraction, capsomers started apart take the solvent's temperature through
#   collisions alone (the thermostat acts on the solvent only), in translation and rotation;
#   with an implicit solvent (Langevin capsomers) they reach its temperature in both;
#   a run continued from a checkpoint ends as the straight run does, and its cluster-event
#   tallies go on from the checkpoint's (60 monomers seen at each of 9 intervals: 540; the
#   coarse tallies, every second sample, 60 at each of 4 intervals: 240, with the checkpoint
#   between two of their samples);
#   a seeded cluster (start=cluster) is one cluster of cluster_size members: a dimer has 1 bond,
#   the trimer is fully bonded (3), 59 members are the shell less one (150 - 5 = 145 bonds);
#   the table1 preset starts the paper's Table 1 system (244625 particles);
#   cluster-event tallies taken every 25 steps between samples 100 apart (events_every) are
#   those of samples every 25 steps, exactly (the censuses change nothing); continued at the same
#   interval they go on as the straight run's, at another they start afresh (what they hold is
#   then the clusters of the new censuses alone).
# usage: capsid_assembly_tiny.sh EMERGENT MPIRUN
set -euo pipefail
exe=$1
mpirun=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
common=(--preset tiny --set progress_interval=0)
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "$mpirun" -q --oversubscribe -np 2 \
  "$exe" run capsid-assembly "${common[@]}" --set attraction=0.09 --set seed=31 --set steps=4000 \
  --set sample_every=250 -o "$dir/bound" >/dev/null
"$exe" run capsid-assembly "${common[@]}" --set shape=ph --set attraction=0.09 --set seed=31 --set steps=4000 \
  --set sample_every=250 -o "$dir/ph" >/dev/null
"$exe" run capsid-assembly "${common[@]}" --set attraction=0 --set seed=31 --set steps=4000 \
  --set sample_every=250 -o "$dir/free" >/dev/null
"$exe" run capsid-assembly "${common[@]}" --set attraction=0 --set start=monomers --set seed=4242 \
  --set steps=30000 --set sample_every=500 -o "$dir/monomers" >/dev/null
"$exe" run capsid-assembly "${common[@]}" --set attraction=0 --set start=monomers --set seed=99 \
  --set solvent=implicit --set friction_translation=1 --set friction_rotation=1 --set steps=6000 \
  --set sample_every=100 -o "$dir/implicit" >/dev/null
part=(--preset tiny --set progress_interval=0 --set attraction=0.05 --set start=monomers
      --set sample_every=200)
"$exe" run capsid-assembly "${part[@]}" --set steps=2000 -o "$dir/straight" >/dev/null
"$exe" run capsid-assembly "${part[@]}" --set steps=1000 --checkpoint-every 1000 -o "$dir/part" >/dev/null
"$exe" run --restart "$dir/part/checkpoint.h5" --set steps=2000 -o "$dir/part" >/dev/null
for n in 2 3 59; do
  "$exe" run capsid-assembly --set progress_interval=0 --set capsomers=80 --set solvent=implicit \
    --set start=cluster --set cluster_size=$n --set steps=10 --set sample_every=10 -o "$dir/cluster$n" >/dev/null
done
events=(--set progress_interval=0 --set capsomers=60 --set particle_fraction=0.033 --set solvent=implicit
        --set attraction=0.12 --set seed=7 --set steps=8000)
"$exe" run capsid-assembly "${events[@]}" --set sample_every=25 -o "$dir/events_sampled" >/dev/null
"$exe" run capsid-assembly "${events[@]}" --set sample_every=100 --set events_every=25 -o "$dir/events_between" >/dev/null
"$exe" run capsid-assembly "${events[@]}" --set sample_every=100 --set events_every=25 --set steps=4000 \
  --checkpoint-every 4000 -o "$dir/events_part" >/dev/null
"$exe" run --restart "$dir/events_part/checkpoint.h5" --set steps=8000 -o "$dir/events_same" >/dev/null
"$exe" run --restart "$dir/events_part/checkpoint.h5" --set steps=8000 --set events_every=50 \
  --set sample_every=50 -o "$dir/events_other" >/dev/null
if [ "$(tail -n 1 "$dir/straight/thermo.dat")" != "$(tail -n 1 "$dir/part/thermo.dat")" ]; then
  echo "FAIL: the continued run does not end as the straight run"; exit 1
fi
# The table1 preset is the paper's Table 1 system: N = 1.25e5 at p = 0.033 with each capsomer
# once, so 4125 capsomers of 30 particles (10 spheres, 20 sites) and 120875 solvent atoms.
"$exe" run capsid-assembly --preset table1 --set steps=2 --set progress_interval=0 --set output.every=0 \
  --set checkpoint_every=0 -o "$dir/table1" >/dev/null
/usr/bin/python3 - "$dir" <<'PY'
import sys
import h5py, numpy as np
d = sys.argv[1]
def series(run, name):
    with h5py.File(f"{d}/{run}/trajectory.h5", "r") as f:
        g = f["observables"][name]
        v = g["value"][:]
        return g["step"][:], v.ravel() if v.ndim == 2 and v.shape[1] == 1 else v
fail = []
_, bonds = series("bound", "bonds")
_, shells = series("bound", "complete_shells")
print(f"e=0.09: bonds {int(bonds.min())}..{int(bonds.max())}, complete shells {int(shells.min())}..{int(shells.max())} over {len(bonds)} samples")
if bonds.min() != 150 or shells.min() != 1:
    fail.append("the closed shell did not stay closed at e=0.09")
_, bonds = series("ph", "bonds")
_, shells = series("ph", "complete_shells")
print(f"PH design, e=0.09: bonds {int(bonds.min())}..{int(bonds.max())}, complete shells {int(shells.min())}..{int(shells.max())}")
if bonds.min() != 150 or shells.min() != 1:
    fail.append("the closed PH shell did not stay closed at e=0.09")
_, largest = series("free", "largest_cluster")
_, fbonds = series("free", "bonds")
print(f"e=0: largest cluster {int(largest[0])} at the first sample, {int(largest[-1])} at the end; bonds at the end {int(fbonds[-1])}")
if largest[-1] > 5:
    fail.append("the shell without attraction did not fall apart")
step, caps = series("monomers", "capsomer_temperature")
_, solvent = series("monomers", "solvent_temperature")
# After 10000 steps (50 tau; rotation relaxes over ~25 tau from its start), 40 samples over
# 100 tau. A 60-body temperature fluctuates by sqrt(2/180) = 0.105 per sample; with a
# correlation time of ~10 tau there are >= 10 independent samples, a standard error <= 0.033,
# so 0.12 is ~3.6 standard errors.
late = step > 10000
t_trans, t_rot = caps[late, 0].mean(), caps[late, 1].mean()
t_solvent = solvent[late].mean()
print(f"e=0, monomers: solvent T {t_solvent:.3f}, capsomers translation {t_trans:.3f}, rotation {t_rot:.3f}")
for name, t in (("translational", t_trans), ("rotational", t_rot)):
    if abs(t - t_solvent) > 0.12:
        fail.append(f"capsomers' {name} temperature {t:.3f} is not the solvent's {t_solvent:.3f}")
step, caps = series("implicit", "capsomer_temperature")
late = step > 1000  # 5 relaxation times (rates 1/tau)
# Langevin at rate 1: samples 0.5 tau apart are nearly independent; 50 samples of a 60-body
# temperature (sd 0.105 each) give a standard error of 0.015; 0.06 is 4 of them.
t_trans, t_rot = caps[late, 0].mean(), caps[late, 1].mean()
print(f"implicit solvent: capsomers translation {t_trans:.3f}, rotation {t_rot:.3f} (target 1)")
for name, t in (("translational", t_trans), ("rotational", t_rot)):
    if abs(t - 1) > 0.06:
        fail.append(f"implicit solvent: capsomers' {name} temperature {t:.3f} is not 1")
import json
seen = [json.load(open(f"{d}/{r}/summary.json"))["scene_measures"]["clusters_seen"][0]
        for r in ("straight", "part")]
print(f"continued run: monomers seen {seen[1]:.0f} (straight run {seen[0]:.0f})")
if seen != [540, 540]:
    fail.append("the cluster-event tallies did not go on across the checkpoint")
coarse = [json.load(open(f"{d}/{r}/summary.json"))["scene_measures"]["clusters_seen_coarse"][0]
          for r in ("straight", "part")]
print(f"continued run, coarse tallies: monomers seen {coarse[1]:.0f} (straight run {coarse[0]:.0f})")
if coarse != [240, 240]:
    fail.append("the coarse cluster-event tallies did not go on across the checkpoint")
for n, expected in ((2, 1), (3, 3), (59, 145)):
    m = json.load(open(f"{d}/cluster{n}/summary.json"))["scene_measures"]
    print(f"start=cluster, {n} members: largest {m['largest_cluster']:.0f}, bonds {m['bonds']:.0f}, "
          f"clusters {m['clusters']:.0f}")
    if (m["largest_cluster"], m["bonds"], m["clusters"]) != (n, expected, 80 - n + 1):
        fail.append(f"the seeded cluster of {n} is not one cluster with {expected} bonds")
    # By size: the seed and 80 - n monomers; the seeded trimer is fully bonded (a closed ring).
    by_size = [0] * 60
    by_size[0], by_size[n - 1] = 80 - n, 1
    if m["clusters_by_size"] != by_size or m["closed_trimers"] != (1 if n == 3 else 0):
        fail.append(f"the seeded cluster of {n}: clusters_by_size has {[(k + 1, v) for k, v in enumerate(m['clusters_by_size']) if v]}, "
                    f"closed_trimers {m['closed_trimers']}")
n_table1 = json.load(open(f"{d}/table1/summary.json"))["N"]
print(f"table1 preset: {n_table1} particles")
if n_table1 != 120875 + 4125 * 30:
    fail.append(f"the table1 preset has {n_table1} particles, not Table 1's system (244625)")
tallies = [name + suffix for suffix in ("", "_coarse")
           for name in ("growth_events", "loss_events", "clusters_seen", "split_events", "pieces_shed",
                        "merge_events", "assembled_from_monomers")]
ev = {r: json.load(open(f"{d}/events_{r}/summary.json"))["scene_measures"] for r in ("sampled", "between", "same", "other")}
print(f"event tallies every 25 steps: {sum(ev['sampled']['growth_events']):.0f} growth, "
      f"{sum(ev['sampled']['loss_events']):.0f} loss events from samples; "
      f"{sum(ev['between']['growth_events']):.0f}, {sum(ev['between']['loss_events']):.0f} between samples 100 apart")
if sum(ev["sampled"]["growth_events"]) < 2:
    fail.append("too few growth events to compare the tallies")
print("pieces shed, merges, clusters assembled from monomers (between samples): "
      f"{sum(ev['between']['pieces_shed']):.0f}, {sum(ev['between']['merge_events']):.0f}, "
      f"{sum(ev['between']['assembled_from_monomers']):.0f}")
if any(ev["sampled"][k] != ev["between"][k] for k in tallies):
    fail.append("tallies between samples (events_every) differ from those of samples at that interval")
if any(ev["same"][k] != ev["between"][k] for k in tallies):
    fail.append("tallies continued at the same events_every differ from the straight run's")
# Afresh at 50 steps: each census but the last counts its clusters once, so the monomers-and-all
# seen are the clusters sampled at 4050 .. 7950 (samples every 50 steps), nothing from before.
with h5py.File(f"{d}/events_other/" + [f for f in __import__("os").listdir(f"{d}/events_other") if f.startswith("trajectory.from") and f.endswith(".h5")][0], "r") as f:
    steps_other = f["observables/clusters/step"][:]
    clusters_other = np.asarray(f["observables/clusters/value"][:], float).ravel()
expected_seen = clusters_other[(steps_other >= 4050) & (steps_other <= 7950)].sum()
print(f"continued at events_every=50: clusters seen {sum(ev['other']['clusters_seen']):.0f}, the new censuses' {expected_seen:.0f}")
if sum(ev["other"]["clusters_seen"]) != expected_seen:
    fail.append("tallies continued at another events_every did not start afresh")
if fail:
    sys.exit("FAIL: " + "; ".join(fail))
print("ok")
PY
