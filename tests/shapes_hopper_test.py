#!/usr/bin/python3
"""studies/seed002/shapes_hopper.py's stopping rules on synthetic remaining-fraction series: a
12 s case is done at 12 s; the long case at its full duration, or earlier once no grain has left
for STOPPED seconds after the 12 s, never while grains still leave or before 12 s + STOPPED."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies" / "seed002"))
import shapes_hopper as sh  # noqa: E402

failures = []


def series(t_end, flat_from=None, dt=0.05):
    """Draining at 10 grains a second out of 2000, constant from flat_from on."""
    t = [k * dt for k in range(int(round(t_end / dt)) + 1)]
    f = [1.0 - 10 * min(x, flat_from if flat_from is not None else x) / 2000 for x in t]
    return {"time": t, "remaining_fraction": f}


def check(name, got, want):
    if got != want:
        failures.append(f"{name}: {got}, expected {want}")


short, long_ = sh.done_for("hollow_block"), sh.done_for("hollow_block_long")
check("12 s case at 11.9 s", short(series(11.9)), False)
check("12 s case at 12 s", short(series(12.0)), True)
check("12 s case stalled at 11 s is not done early", short(series(11.5, flat_from=5.0)), False)
check("long case draining at 20 s", long_(series(20.0)), False)
check("long case stalled for 1 s", long_(series(20.0, flat_from=19.0)), False)
check("long case stalled for 2.5 s", long_(series(20.0, flat_from=17.5)), True)
check("long case stalled since 5 s, at 13 s (before 12 s + STOPPED)", long_(series(13.0, flat_from=5.0)), False)
check("long case stalled since 5 s, at 14.5 s", long_(series(14.5, flat_from=5.0)), True)
check("long case at its duration", long_(series(sh.duration_of("hollow_block_long"))), True)
check("long case overrides its duration", "run.duration=40.0" in sh.overrides("hollow_block_long"), True)
check("long case runs the hollow block", 'shape.0.path="data/shapes/hollow_block.obj"' in sh.overrides("hollow_block_long"), True)
check("12 s case keeps the scene's duration", any(o.startswith("run.duration") for o in sh.overrides("tetrapod")), False)
check("long case is stopped by the stall test while it runs", sh.stop_for("hollow_block_long") is sh.stopped, True)
check("12 s case has no stop test", sh.stop_for("tetrapod"), None)
if failures:
    print("\n".join(failures))
    sys.exit(1)
print("shapes_hopper stopping rules: all checks pass")
