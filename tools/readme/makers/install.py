"""The manual's table of the README commands' wall times, from the committed fresh-clone log
(docs/install/fresh_clone.log, written by tools/fresh_clone.sh)."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
WHAT = {1: "install the program's packages, build `grainflow`, run the default scene",
        2: "install the rest, build everything, run the fast test suite"}


def install_times(path="docs/install/fresh_clone.log"):
    text = (ROOT / path).read_text()
    head = text.splitlines()[:3]
    rows = ["| command | what it does | exit status | wall time |", "|---|---|---|---|"]
    for n, rc, s in re.findall(r"^## command (\d+): exit status (\d+), wall time (\d+) s$", text, re.M):
        s = int(s)
        rows.append(f"| {n} | {WHAT.get(int(n), '')} | {rc} | {s} s ({s // 60} min {s % 60:02d} s) |")
    tests = re.search(r"^(\d+)% tests passed, (\d+) tests failed out of (\d+)", text, re.M)
    total = re.search(r"^Total Test time \(real\) = +([\d.]+) sec", text, re.M)
    rows.append("")
    commit = re.search(r"fresh clone of (\w+) \(([\d-]+)\)", head[0])
    machine = head[1].split("machine: ", 1)[1]
    purged = head[2].endswith("yes")
    rows.append(f"A fresh clone of commit {commit.group(1)[:12]} ({commit.group(2)}) on {machine}"
                + ("; the project's Debian packages removed first." if purged else "."))
    if tests:
        rows.append(f"The fast suite: {tests.group(3)} tests, {tests.group(2)} failed"
                    + (f", {float(total.group(1)):.0f} s of the second command." if total else "."))
    return "\n".join(rows) + "\n"


TABLES = {"install_times": install_times}
