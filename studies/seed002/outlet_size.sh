#!/usr/bin/env bash
# Seed 002's hopper (case 1) with the grains scaled against the fixed 40 mm gate: the gate is
# 40 mm / SIDE prism sides wide. Every size is poured the same way, from a lattice of bounding
# spheres reaching 2.2 m (room for 1000 of the largest), settled for 1.5 s; the pour's impacts
# overlap more than the scenes' own shorter pour, so run.max_overlap is 0.3 (the discharge's
# overlaps stay far below it: max_overlap_ratio in series.csv). Then archives the run's series,
# summary, final frame and the pictures at the times given.
#
#   studies/seed002/outlet_size.sh prisms|cones SIDE_MM RUN_DIR [DOCS_DIR [PICTURE_TIMES...]]
#   studies/seed002/outlet_size.sh archive RUN_DIR DOCS_DIR [PICTURE_TIMES...]    (a finished run)
#   e.g. studies/seed002/outlet_size.sh prisms 13.333 runs/seed002_outlet/prisms_side13.3 \
#          studies/seed002/results/outlet/prisms_side13.3 1.4 2.0 3.0
# Environment: GRAINFLOW (default build/grainflow), THREADS (default 1), SEED (the fill's orientation
# seed, bodies.2.seed; the scenes' own when unset): another SEED is another pour of the same grains.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
usage() { sed -n '9,12p' "${BASH_SOURCE[0]}" >&2; exit 2; }
[ $# -ge 3 ] || usage
archive() {  # RUN_DIR DOCS_DIR [PICTURE_TIMES...]
  local out="$1" docs="$2"
  shift 2
  if ! grep -q '"status": "completed"' "$out/summary.json"; then
    echo "outlet_size: $out did not complete (see its summary.json); not archived" >&2
    exit 1
  fi
  mkdir -p "$docs"
  cp "$out/series.csv" "$out/summary.json" "$docs/"
  cp "$(ls "$out"/frames/frame_0*.csv | sort | tail -1)" "$docs/final_frame.csv"
  for t in "$@"; do cp "$out/pictures/$(printf 'time_%09.4f.png' "$t")" "$docs/"; done
}
if [ "$1" = archive ]; then
  shift
  cd "$REPO"
  archive "$@"
  exit 0
fi
shape="$1" side_mm="$2" out="$3" docs="${4:-}"
shift 4 2>/dev/null || shift $#
bin="${GRAINFLOW:-$REPO/build/grainflow}"
s=$(python3 -c "print($side_mm / 1000)")
case "$shape" in
  prisms) scene=scenes/hopper_seed002_prisms.toml
          size=(--set "shape.0.side=$s" --set "shape.0.length=$s") ;;
  cones)  scene=scenes/hopper_seed002_cones.toml  # the 10 mm element scaled: corners, neck, each part's height
          k=$(python3 -c "print($side_mm / 10)")
          size=(--set "shape.0.base_radius=$(python3 -c "print(round($s / 3 ** 0.5, 7))")"
                --set "shape.0.neck_radius=$(python3 -c "print(round(0.0025 * $k, 7))")"
                --set "shape.0.height=$(python3 -c "print(round(0.005 * $k, 7))")") ;;
  *) echo "shape: prisms or cones" >&2; exit 2 ;;
esac
cd "$REPO"
"$bin" run "$scene" --out "$out" --threads "${THREADS:-1}" --quiet "${size[@]}" \
  --set 'bodies.2.region={shape="box", lo=[-0.07,0.03,-0.025], hi=[0.07,2.2,0.025]}' \
  --set settle.time=1.5 --set run.max_overlap=0.3 ${SEED:+--set bodies.2.seed=$SEED}
[ -z "$docs" ] && exit 0
archive "$out" "$docs" "$@"
