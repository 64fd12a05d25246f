#!/usr/bin/env bash
# Strong and weak scaling of distributed rigid runs (issue 6). Needs Open MPI (see .ci/run).
#
#   bash benches/scaling.sh            # writes bench-results/scaling/*.json and prints a table
#
# Strong scaling: the same scene on 1 and 2 processes, each with --compare-serial (the serial
# time of the same steps is measured in the same invocation, right after the distributed run).
#   - box10k, all 1500 steps (deposit: fall, collapse, settled bed);
#   - box100k, the first STEPS_100K steps (default 100: free fall and first contacts), and
#     its dense phase: a serial run to step 400 writes a checkpoint (the lower rows packed,
#     16,800 contacts, sweeps at the 1000 cap), then steps 401 to 450 are resumed from it
#     serially and on 2 processes.
#   - nooru_mohamed (the paper's mesh, 36,351 elements), the first STEPS_NM steps (default
#     500: loading, damage at both notches).
#   - two_grains_sedimentation (64 x 640 cells, the paper's mesh), the first STEPS_FLUID steps
#     (default 2000: 0.2 s of fall), and glowinski_sedimentation (160 x 640 cells), the first
#     DURATION_GLOWINSKI seconds (default 0.5), and suspension_settling (300 grains,
#     512 x 1024 cells), the first DURATION_SUSPENSION seconds (default 0.1); each pair runs
#     REPEAT_FLUID times (default 4). Beside each fluid pair, the machine's own ceiling at that
#     moment: the same scene run twice at once, serially (no communication, no imbalance; the
#     serial time alone over the slower of the two is the efficiency the machine allowed), and
#     xper-domain-sync-ceiling (equal strips of a grid relaxed and exchanged as often as the
#     pressure multigrid does, against one process relaxing the whole grid).
# Weak scaling: a deposit of 2500 disks per process on 1, 2 and 4 processes (oversubscribed on
# a 2-core machine), 300 steps; and a fluid column of 64 x 320 cells per process with one
# grain per block, 300 steps; reported as communication volume per step per process.
# CASES (default "rigid fracture fluid weak weakfluid") selects parts; the table and scaling.json cover every
# run found under bench-results/scaling.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_mpi_yield_when_idle=1
STEPS_100K=${STEPS_100K:-100}
STEPS_NM=${STEPS_NM:-500}
STEPS_FLUID=${STEPS_FLUID:-2000}
DURATION_GLOWINSKI=${DURATION_GLOWINSKI:-0.5}
DURATION_SUSPENSION=${DURATION_SUSPENSION:-0.1}
CASES=${CASES:-rigid fracture fluid weak weakfluid}
cargo build --release -p xper-cli --features mpi
cargo build --release -p xper-domain --features mpi --bin xper-domain-sync-ceiling
XPER=target/release/xper
OUT=bench-results/scaling
mkdir -p "$OUT/scenes"

run() { # processes scene out [extra...]
  local np=$1 scene=$2 out=$3; shift 3
  rm -rf "$out"
  timeout 7200 mpirun -np "$np" "$XPER" run "$scene" --out "$out" --quiet "$@"
}

# Strong scaling: outputs only at the end (frames and checkpoints are not the measure); the
# serial reference is also run alone (no other process on the machine) with the plain binary.
no_outputs() { printf '\n[output]\nframe_every = %s\ncheckpoint_every = %s\n' "$1" "$1"; }
{ cat scenes/box10k/scene.toml; no_outputs 1500; } > "$OUT/scenes/box10k.toml"
{ sed "s/^steps = .*/steps = $STEPS_100K/" scenes/box100k/scene.toml; no_outputs "$STEPS_100K"; } \
  > "$OUT/scenes/box100k_head.toml"
sed -e "s/^steps = .*/steps = $STEPS_NM/" -e "s/^frame_every = .*/frame_every = $STEPS_NM/" \
  -e "s/^checkpoint_every = .*/checkpoint_every = $STEPS_NM/" scenes/nooru_mohamed/scene.toml \
  > "$OUT/scenes/nooru_mohamed_head.toml"
fluid_head() { # scene duration
  sed -e "s/^duration = .*/duration = $2/" -e "s/^frame_every = .*/frame_every = 1000000/" \
    -e "s/^checkpoint_every = .*/checkpoint_every = 1000000/" "scenes/$1/scene.toml"
}
fluid_head two_grains_sedimentation "$(python3 -c "print($STEPS_FLUID * 1e-4)")" \
  > "$OUT/scenes/two_grains_head.toml"
fluid_head glowinski_sedimentation "$DURATION_GLOWINSKI" > "$OUT/scenes/glowinski_head.toml"
fluid_head suspension_settling "$DURATION_SUSPENSION" > "$OUT/scenes/suspension_head.toml"
strong=()
[[ " $CASES " == *" rigid "* ]] && strong+=(box10k box100k_head)
{ sed "s/^steps = .*/steps = 450/" scenes/box100k/scene.toml; printf '\n[output]\nframe_every = 450\ncheckpoint_every = 400\n'; } \
  > "$OUT/scenes/box100k_dense.toml"
[[ " $CASES " == *" fracture "* ]] && strong+=(nooru_mohamed_head)
[[ " $CASES " == *" fluid "* ]] && strong+=(two_grains_head glowinski_head suspension_head)
serial_pair() { # scene out: two serial runs of scene at once, into out/a and out/b
  rm -rf "$2"
  "$XPER" run "$1" --out "$2/a" --quiet &
  local first=$! status=0
  "$XPER" run "$1" --out "$2/b" --quiet || status=$?
  wait "$first" || status=$?
  return "$status"
}
fluid_scenes=(two_grains_head glowinski_head suspension_head)
for name in "${strong[@]}"; do
  scene="$OUT/scenes/$name.toml"
  rm -rf "$OUT/serial_$name"
  "$XPER" run "$scene" --out "$OUT/serial_$name" --quiet
  [[ " ${fluid_scenes[*]} " == *" $name "* ]] && serial_pair "$scene" "$OUT/pair_$name"
  run 2 "$scene" "$OUT/strong_${name}_np2" --compare-serial
done
# The fluid pairs are short (seconds): repeated REPEAT_FLUID times, serial alone, two serial
# runs at once, then 2 processes, since on this shared 2-core machine the two cores do not
# always run at the same speed, nor two processes at once as fast as one alone.
if [[ " $CASES " == *" fluid "* ]]; then
  for ((k = 1; k <= ${REPEAT_FLUID:-4}; k++)); do
    suffix=$([[ $k -gt 1 ]] && echo "_r$k" || true)
    timeout 600 mpirun -np 2 target/release/xper-domain-sync-ceiling \
      --out "$OUT/strong_sync_ceiling_np2$suffix"
    [[ $k -eq 1 ]] && continue
    for name in "${fluid_scenes[@]}"; do
      scene="$OUT/scenes/$name.toml"
      rm -rf "$OUT/serial_${name}$suffix"
      "$XPER" run "$scene" --out "$OUT/serial_${name}$suffix" --quiet
      serial_pair "$scene" "$OUT/pair_${name}$suffix"
      run 2 "$scene" "$OUT/strong_${name}_np2$suffix" --compare-serial
    done
  done
fi

# box100k's dense phase, resumed from the serial run's checkpoint at step 400.
if [[ " $CASES " == *" rigid "* ]]; then
  scene="$OUT/scenes/box100k_dense.toml"
  base="$OUT/box100k_dense_base"
  rm -rf "$base"
  "$XPER" run "$scene" --out "$base" --quiet --stop-at-step 400
  for out in serial_box100k_dense strong_box100k_dense_np2; do
    rm -rf "${OUT:?}/$out"
    cp -r "$base" "$OUT/$out"
  done
  "$XPER" run "$scene" --out "$OUT/serial_box100k_dense" --quiet --resume
  timeout 7200 mpirun -np 2 "$XPER" run "$scene" --out "$OUT/strong_box100k_dense_np2" --quiet \
    --resume --compare-serial
  rm -rf "$base"
fi

# Weak scaling.
[[ " $CASES " == *" weak "* ]] && for np in 1 2 4; do
  count=$((2500 * np))
  width=$(python3 -c "print(0.1 * $count / 300.0)")
  cat > "$OUT/scenes/weak_np$np.toml" <<TOML
[scene]
name = "weak_np$np"
dt = 2e-4
steps = 300
alert_distance = 5e-4

[output]
frame_every = 300
checkpoint_every = 300

[[materials]]
name = "glass"
density = 2500.0

[[laws]]
between = ["grains", "grains"]
kind = "signorini_coulomb"
friction = 0.3

[[laws]]
between = ["grains", "walls"]
kind = "signorini_coulomb"
friction = 0.5

[[generators]]
kind = "box_of_disks"
count = $count
radius = [0.002, 0.003]
box = [[0.0, 0.0], [$width, 0.15]]
placement = "random"
seed = 7
material = "glass"
group = "grains"
walls = "walls"
TOML
  run "$np" "$OUT/scenes/weak_np$np.toml" "$OUT/weak_np$np"
done

# Weak scaling of the fluid: a column 64 cells wide and 320 rows high per process (the paper's
# two-grain mesh, h = 5e-5 m), one grain falling in each process's block, 300 steps.
[[ " $CASES " == *" weakfluid "* ]] && for np in 1 2 4; do
  height=$(python3 -c "print(0.016 * $np)")
  {
    cat <<TOML
[scene]
name = "weakfluid_np$np"
dt = 1e-4
duration = 0.03
gravity = [0.0, -9.81]

[output]
frame_every = 1000000
checkpoint_every = 1000000

[[materials]]
name = "grain"
density = 1200.0

[[laws]]
between = ["grain", "wall"]
kind = "signorini_coulomb"
friction = 0.5

[[walls]]
from = [0.0, 0.0]
to = [0.0032, 0.0]
group = "wall"

[fluid]
density = 1000.0
viscosity = 4e-3
domain = [[0.0, 0.0], [0.0032, $height]]
cells_per_diameter = 16
TOML
    for ((k = 0; k < np; k++)); do
      printf '\n[[bodies]]\nshape = "disk"\ncenter = [0.0016, %s]\nradius = 0.0004\nmaterial = "grain"\ngroup = "grain"\n' \
        "$(python3 -c "print(0.016 * $k + 0.008)")"
    done
  } > "$OUT/scenes/weakfluid_np$np.toml"
  run "$np" "$OUT/scenes/weakfluid_np$np.toml" "$OUT/weakfluid_np$np"
done

python3 - "$OUT" <<'PY'
import json, sys, os
out = sys.argv[1]
rows = {}
for d in sorted(os.listdir(out)):
    p = os.path.join(out, d, "summary.json")
    if os.path.exists(p):
        rows[d] = json.load(open(p))
# The machine's ceiling beside a fluid pair: the serial run alone over the slower of two at once.
wall = lambda p: json.load(open(p))["wall_time_s"]
for d in sorted(os.listdir(out)):
    if d.startswith("pair_") and os.path.exists(os.path.join(out, d, "b", "summary.json")):
        name, _, suffix = d[len("pair_"):].partition("_head")
        alone = os.path.join(out, f"serial_{name}_head{suffix}", "summary.json")
        strong = f"strong_{name}_head_np2{suffix}"
        if strong in rows and os.path.exists(alone):
            alone = wall(alone)
            pair = [wall(os.path.join(out, d, x, "summary.json")) for x in "ab"]
            rows[strong]["machine_ceiling"] = {"serial_alone_s": alone, "two_at_once_s": pair,
                                               "efficiency": alone / max(pair)}
json.dump(rows, open(os.path.join(out, "scaling.json"), "w"), indent=1)
print("| run | processes | steps | wall (s) | serial (s) | speed-up | efficiency | machine ceiling | max |dx| (m) | comm share (max rank) | bytes / step / rank | messages / step / rank |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for d, s in rows.items():
    ranks = s.get("ranks", [])
    steps = max(s["steps"] - s.get("first_step", 0), 1)
    c = s.get("serial_comparison") or {}
    if s.get("first_step", 0) > 0:  # resumed: the wall time of this invocation's steps
        import csv
        series = csv.DictReader(open(os.path.join(out, d, "series.csv")))
        s["wall_time_s"] = sum(float(r["wall_time"]) for r in series if int(r["step"]) > s["first_step"])
    share = max((r["communication_share"] for r in ranks), default=0)
    bytes_ = sum(r["bytes"] for r in ranks) / steps / max(len(ranks), 1)
    msgs = sum(r["messages"] for r in ranks) / steps / max(len(ranks), 1)
    fmt = lambda x, f: (f % x) if x != "" else "-"
    print(f"| {d} | {s['processes']} | {steps} | {c.get('distributed_wall_time_s', s['wall_time_s']):.2f} | "
          f"{fmt(c.get('serial_wall_time_s', ''), '%.2f')} | {fmt(c.get('speed_up', ''), '%.2f')} | "
          f"{fmt(c.get('efficiency', ''), '%.2f')} | {fmt(s.get('machine_ceiling', {}).get('efficiency', ''), '%.2f')} | "
          f"{fmt(c.get('max_position_difference_m', ''), '%.1e')} | "
          f"{share:.2f} | {bytes_:.0f} | {msgs:.0f} |")
PY
