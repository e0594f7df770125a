#!/usr/bin/python3
"""studies/seed002/letter_convexity.py against closed forms: the faces of O, T and C are unions of
rectangles whose areas and hulls are known exactly, and a convex plate has convexity 1. The face
area is counted on a grid of 0.2 mm cells, so it may differ from the exact area by the cells the
boundary cuts (a few tenths of a per cent of these faces): the tolerance is 0.5 %. Hulls are exact."""
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "studies" / "seed002"))
import letter_convexity as lc  # noqa: E402

L, H = 0.100, 0.180
failures = []


def close(name, got, want, rel):
    if abs(got - want) > rel * abs(want):
        failures.append(f"{name}: {got} against {want} (tolerance {rel:.1%})")


for s in (0.02, 0.03, 0.04):
    o, t, c = (lc.measure(x, L, H, s) for x in "OTC")
    close(f"O area, s={s}", o["area_cm2"], (L * H - (L - 2 * s) * (H - 2 * s)) * 1e4, 0.005)
    close(f"O hull, s={s}", o["hull_cm2"], L * H * 1e4, 1e-9)
    close(f"T area, s={s}", t["area_cm2"], (L * s + s * (H - s)) * 1e4, 0.005)
    # T's hull: the bar on top and the stem's foot, a trapezoid of heights s (bar) and H - s.
    close(f"T hull, s={s}", t["hull_cm2"], (L * s + (L + s) / 2 * (H - s)) * 1e4, 1e-9)
    close(f"C area, s={s}", c["area_cm2"], (s * H + 2 * (L - s) * s) * 1e4, 0.005)
    close(f"C hollow, s={s}", c["hollow_cm2"], (L - s) * (H - 2 * s) * 1e4, 0.01)
# A convex plate: one rectangle has convexity 1 (through the same measure, on a stand-in layout).
orig = lc.layout
lc.layout = lambda letter, L_, H_, s: [lc.rect(-L_ / 2, L_ / 2, -H_ / 2, H_ / 2)]
close("rectangle convexity", lc.measure("O", L, H, 0.03)["convexity"], 1.0, 0.005)
lc.layout = orig
# Rank correlation: identical orders give 1, reversed ones -1.
a = {k: float(i) for i, k in enumerate("OTZKAC")}
close("spearman same", lc.spearman(a, a), 1.0, 1e-12)
close("spearman reversed", lc.spearman(a, {k: -v for k, v in a.items()}), -1.0, 1e-12)
if failures:
    print("\n".join(failures))
    sys.exit(1)
print("letter_convexity: closed forms matched")
