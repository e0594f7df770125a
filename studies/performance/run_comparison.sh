#!/usr/bin/env bash
# Side-by-side speed of LIGGGHTS 3.8 and grainflow on a benchmark state of the seed-000 drum
# (47,108 grains), in one time window. STATE picks it:
#   settled  (default) scenes/drum_seed000_settled.toml: the poured and settled bed at rest; its first
#            2,000 steps turn the bed as a rigid body (few contacts change, few rebuilds)
#   flowing  scenes/drum_seed000_flowing.toml: the shared state after 1.5 s of rotation (LIGGGHTS),
#            positions and velocities, the surface avalanching: the workload of a real run
#   grainflow  scenes/drum_seed000_flowing_grainflow.toml: grainflow's own state after 3 s of
#            rotation from the settled bed, positions, velocities and spins
# Both codes start from the same file (make_inputs.py writes its velocities and spins for LIGGGHTS).
#
#   studies/performance/run_comparison.sh [BUILD_DIR]        (default BUILD_DIR: <repo>/build)
#
# Builds nothing. Writes the LIGGGHTS inputs (make_inputs.py) into a work folder, then runs, for
# STEPS steps each, in the order LIGGGHTS 1 rank, grainflow 1 thread, LIGGGHTS 2 ranks, grainflow
# 2 threads, and all that REPEATS times. Prints every run, then a table of median wall time and
# particle-steps/s with the ratios grainflow / LIGGGHTS at 1 and at 2, and the LIGGGHTS timing
# breakdown of its 1-rank runs.
#   LIGGGHTS:  wall = its "Loop time" (the run loop only), particle-steps/s = steps x atoms / wall
#   grainflow: wall = summary.json wall_seconds (the main stage only), particle_steps_per_second
# Environment: STATE (settled), STEPS (2000), REPEATS (2), WORK (work folder; default a new /tmp/liggghts_cmp.*),
#              ROLLING (LIGGGHTS rolling model for make_inputs.py, default epsd),
#              SKIN (Verlet skin in m given to both codes; default the scene's, 1.5e-4),
#              MPI=1 adds to each round, last, grainflow_mpi on 2 ranks of 1 thread each (BUILD_DIR's
#              grainflow_mpi): the two codes' domain decompositions side by side.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
BUILD="$(cd "${1:-$REPO/build}" 2>/dev/null && pwd || echo "${1:-$REPO/build}")"
STEPS="${STEPS:-2000}"
REPEATS="${REPEATS:-2}"
ROLLING="${ROLLING:-epsd}"
WORK="${WORK:-$(mktemp -d /tmp/liggghts_cmp.XXXXXX)}"
STATE="${STATE:-settled}"
SKIN="${SKIN:-1.5e-4}"
case "$STATE" in
  settled)   SCENE="scenes/drum_seed000_settled.toml";            CSV="scenes/data/drum_settled_47108.csv" ;;
  flowing)   SCENE="scenes/drum_seed000_flowing.toml";            CSV="scenes/data/drum_flowing_t1.5s_47108.csv" ;;
  grainflow) SCENE="scenes/drum_seed000_flowing_grainflow.toml";  CSV="scenes/data/drum_flowing_grainflow_t3.0s_47108.csv" ;;
  *) echo "run_comparison: STATE must be settled, flowing or grainflow (got '$STATE')" >&2; exit 2 ;;
esac
PY=/usr/bin/python3
MPIRUN=(mpirun --allow-run-as-root --oversubscribe)

command -v liggghts >/dev/null || { echo "run_comparison: liggghts not found (apt-get install liggghts)" >&2; exit 1; }
command -v mpirun >/dev/null || { echo "run_comparison: mpirun not found" >&2; exit 1; }
mkdir -p "$WORK"

echo "# run_comparison: $(date -u +%Y-%m-%dT%H:%M:%SZ), $(nproc --all) cores, load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# cpu: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
# One MPI rank or TBB thread per core; nothing else should spread over the cores.
export OMP_NUM_THREADS=1
echo "# grainflow: $BUILD/grainflow (built $(date -u -r "$BUILD/grainflow" +%H:%M:%SZ 2>/dev/null || echo '?')), repo $(git -C "$REPO" rev-parse --short HEAD 2>/dev/null || echo '?')$(git -C "$REPO" diff --quiet 2>/dev/null || echo ' (working tree modified)')"
echo "# LIGGGHTS: $(command -v liggghts) ($(dpkg-query -W -f='${Version}' liggghts 2>/dev/null || echo '?')), rolling_friction $ROLLING"
echo "# state $STATE: $SCENE ($CSV); $STEPS steps per run, $REPEATS rounds, skin $SKIN m, work folder $WORK"

"$PY" "$HERE/make_inputs.py" "$WORK/inputs" --steps "$STEPS" --rolling "$ROLLING" --csv "$REPO/$CSV" --skin "$SKIN"

# The build folder may be rebuilt by others while this runs: wait (up to 10 min) for the binary.
wait_for_grainflow() {
  local waited=0
  while [ ! -x "$BUILD/grainflow" ]; do
    if [ "$waited" -ge 600 ]; then echo "run_comparison: $BUILD/grainflow missing for 10 min" >&2; return 1; fi
    [ "$waited" -eq 0 ] && echo "# waiting for $BUILD/grainflow to reappear ..." >&2
    sleep 10; waited=$((waited + 10))
  done
  sleep 1  # let a linker finish writing
}

# CPU accounting, in clock ticks, to tell how busy the machine was with other work during a run:
# busy ticks of all cores (/proc/stat) and CPU ticks of this script's finished children.
ticks() {
  local busy own
  busy=$(awk '/^cpu /{print $2 + $3 + $4 + $7 + $8 + $9}' /proc/stat)
  own=$(awk '{print $16 + $17}' "/proc/$$/stat")
  echo "$busy $own"
}

run_liggghts() {  # ranks round
  local n="$1" r="$2" log="$WORK/liggghts_np$1_run$2.log"
  local t0=$EPOCHREALTIME c0
  c0=$(ticks)
  (cd "$WORK/inputs" && "${MPIRUN[@]}" -np "$n" liggghts -in in.drum -log none > "$log" 2>&1) || {
    echo "run_comparison: LIGGGHTS ($n ranks) failed, see $log" >&2; tail -20 "$log" >&2; return 1; }
  echo "liggghts $n $r $log $t0 $EPOCHREALTIME $c0 $(ticks)" >> "$WORK/runs.txt"
}

run_grainflow() {  # threads round
  local n="$1" r="$2" out="$WORK/grainflow_t$1_run$2"
  local t0 c0 rc tries=0
  while :; do
    wait_for_grainflow
    t0=$EPOCHREALTIME
    c0=$(ticks)
    rc=0
    (cd "$REPO" && "$BUILD/grainflow" run "$SCENE" --steps "$STEPS" --threads "$n" --quiet --out "$out" --set "run.skin=$SKIN" \
        > "$out.log" 2>&1) || rc=$?
    [ "$rc" -eq 0 ] && break
    tries=$((tries + 1))
    # a binary being relinked cannot be started (126, 127) or vanishes: wait and retry a few times
    if [ "$tries" -ge 5 ] || { [ "$rc" -ne 126 ] && [ "$rc" -ne 127 ] && [ -x "$BUILD/grainflow" ]; }; then
      echo "run_comparison: grainflow ($n threads) failed (exit $rc), see $out.log" >&2; tail -20 "$out.log" >&2
      return 1
    fi
    sleep 10
  done
  echo "grainflow $n $r $out $t0 $EPOCHREALTIME $c0 $(ticks) $(stat -c %Y "$BUILD/grainflow")" >> "$WORK/runs.txt"
}

run_grainflow_mpi() {  # ranks round (one thread each)
  local n="$1" r="$2" out="$WORK/grainflow_mpi_np$1_run$2"
  local t0=$EPOCHREALTIME c0
  c0=$(ticks)
  (cd "$REPO" && "${MPIRUN[@]}" -np "$n" "$BUILD/grainflow_mpi" run "$SCENE" --steps "$STEPS" --threads 1 --out "$out" \
      --set "run.skin=$SKIN" > "$out.log" 2>&1) || {
    echo "run_comparison: grainflow_mpi ($n ranks) failed, see $out.log" >&2; tail -20 "$out.log" >&2; return 1; }
  echo "grainflow_mpi $n $r $out $t0 $EPOCHREALTIME $c0 $(ticks) $(stat -c %Y "$BUILD/grainflow_mpi")" >> "$WORK/runs.txt"
}

: > "$WORK/runs.txt"
for r in $(seq 1 "$REPEATS"); do
  echo "# round $r: LIGGGHTS 1 rank ..." >&2;    run_liggghts 1 "$r"
  echo "# round $r: grainflow 1 thread ..." >&2; run_grainflow 1 "$r"
  echo "# round $r: LIGGGHTS 2 ranks ..." >&2;   run_liggghts 2 "$r"
  echo "# round $r: grainflow 2 threads ..." >&2; run_grainflow 2 "$r"
  if [ "${MPI:-0}" = 1 ]; then echo "# round $r: grainflow_mpi 2 ranks ..." >&2; run_grainflow_mpi 2 "$r"; fi
done
echo "# done, load: $(cut -d' ' -f1-3 /proc/loadavg)"

"$PY" - "$WORK/runs.txt" "$(getconf CLK_TCK)" <<'EOF'
import json, re, statistics, sys

hz = float(sys.argv[2])
runs = [l.split() for l in open(sys.argv[1]) if l.strip()]
rows, breakdown, mtimes = [], [], set()
loop_re = re.compile(r"Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms")
for rec in runs:
    code, n, rnd, path = rec[:4]
    proc_s = float(rec[5]) - float(rec[4])
    busy0, own0, busy1, own1 = map(float, rec[6:10])
    # cores kept busy by other work meanwhile (all busy CPU time minus this run's own)
    others = max(0.0, ((busy1 - busy0) - (own1 - own0)) / hz / proc_s)
    if code == "liggghts":
        text = open(path).read()
        m = loop_re.search(text)
        if not m:
            sys.exit(f"run_comparison: no 'Loop time' line in {path}")
        wall, steps, atoms = float(m.group(1)), int(m.group(3)), int(m.group(4))
        # last thermo row: step atoms ke_t ke_r
        thermo = [l.split() for l in text.splitlines() if re.match(r"\s*\d+\s+\d+\s+[0-9.eE+-]+\s+[0-9.eE+-]+\s*$", l)]
        ke = float(thermo[-1][2]) if thermo else float("nan")
        if thermo and int(thermo[-1][1]) != atoms:
            print(f"WARNING: {path}: atoms lost ({thermo[-1][1]} of {atoms})")
        psps = steps * atoms / wall
        m = re.search(r"Neighbor list builds = (\d+)", text)
        builds = int(m.group(1)) if m else -1
        if n == "1":
            parts = dict(re.findall(r"^(\w+)\s+time \(%\) = [0-9.eE+-]+ \(([0-9.eE+-]+)\)", text, re.M))
            breakdown.append((rnd, parts))
    else:
        s = json.load(open(path + "/summary.json"))
        if s.get("status") != "completed":
            print(f"WARNING: {path}: status {s.get('status')}")
        wall, steps, psps = s["wall_seconds"], s["steps_this_run"], s["particle_steps_per_second"]
        builds = s.get("neighbor_rebuilds", s.get("neighbour_rebuilds", -1))
        ke = s["final"]["ke_translational"]
        mtimes.add((code, rec[10]))
    rows.append((code, int(n), int(rnd), wall, psps, proc_s, ke, others, builds))

print("\nruns (in the order run)")
print("(wall: the timed loop; process: the whole command, start-up and input included; other load:")
print(" cores kept busy by other processes meanwhile, from /proc/stat - should be near 0)")
print(f"{'code':<10}{'N':>3}{'round':>7}{'wall s':>10}{'process s':>11}{'particle-steps/s':>18}{'KE_t end (J)':>14}{'other load':>12}{'rebuilds':>10}")
for code, n, rnd, wall, psps, proc, ke, others, builds in rows:
    print(f"{code:<10}{n:>3}{rnd:>7}{wall:>10.2f}{proc:>11.2f}{psps:>18.4g}{ke:>14.4g}{others:>12.2f}{builds:>10}")
if max(r[7] for r in rows) > 0.2:
    print("WARNING: other processes used the cores during some runs (other load > 0.2): timings are disturbed")

med = {}
for code in ("liggghts", "grainflow", "grainflow_mpi"):
    for n in (1, 2):
        sel = [r for r in rows if r[0] == code and r[1] == n]
        if sel:
            med[code, n] = (statistics.median(r[3] for r in sel), statistics.median(r[4] for r in sel), len(sel))

print("\nmedians (N = MPI ranks for LIGGGHTS and grainflow_mpi, TBB threads for grainflow)")
print(f"{'code':<10}{'N':>3}{'runs':>6}{'wall s':>10}{'particle-steps/s':>18}")
for (code, n), (w, p, k) in sorted(med.items()):
    print(f"{code:<10}{n:>3}{k:>6}{w:>10.2f}{p:>18.4g}")
print()
for n in (1, 2):
    if ("liggghts", n) in med and ("grainflow", n) in med:
        print(f"grainflow / LIGGGHTS at {n}: {med['grainflow', n][1] / med['liggghts', n][1]:.2f}x particle-steps/s")
if ("grainflow_mpi", 2) in med and ("liggghts", 2) in med:
    print(f"grainflow_mpi / LIGGGHTS at 2 ranks: {med['grainflow_mpi', 2][1] / med['liggghts', 2][1]:.2f}x particle-steps/s")
for code in ("liggghts", "grainflow"):
    if (code, 1) in med and (code, 2) in med:
        print(f"{code} speed-up 1 -> 2: {med[code, 2][1] / med[code, 1][1]:.2f}x")

print("\nLIGGGHTS timing breakdown, 1 rank (% of Loop time; LIGGGHTS 3.8 prints no Modify line:")
print("the fixes - wall/gran on the mesh, move/mesh, nve/sphere, gravity - are all in Other)")
keys = ["Pair", "Neigh", "Comm", "Outpt", "Other"]
print(f"{'round':<7}" + "".join(f"{k:>8}" for k in keys))
for rnd, parts in breakdown:
    print(f"{rnd:<7}" + "".join(f"{float(parts.get(k, 'nan')):>8.1f}" for k in keys))
if len({c for c, _ in mtimes}) < len(mtimes):
    print("\nWARNING: the grainflow binary changed between runs (rebuilt meanwhile); compare with care")
EOF
