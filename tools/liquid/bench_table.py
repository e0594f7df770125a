#!/usr/bin/python3
"""The README's liquid benchmark tables from Google Benchmark's JSON output (--benchmark_out=FILE
--benchmark_out_format=json) of bench/mps_ppe_bench.cpp and bench/mps_step_bench.cpp.

    /usr/bin/python3 tools/liquid/bench_table.py --ppe docs/liquid/bench_ppe.json
    /usr/bin/python3 tools/liquid/bench_table.py --step docs/liquid/bench_step.json

Times are real (wall) times per call, in ms; the line under each table gives the load average that Google
Benchmark recorded when the program started (the machine is shared with other work).
"""
import json
import re
import sys


def load(path):
    data = json.loads(open(path).read())
    runs = {}
    for b in data["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration" or "error_message" in b:
            continue
        family = b["name"].split("/")[0]
        args = dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", b["name"]))
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        b["ms"] = b["real_time"] * scale
        runs[(family, args.get("dim"), args.get("side"), args.get("pc", args.get("eigen")))] = b
    return runs, data["context"]


def tank(dim, side):
    return f"{dim}D {side}^{dim}"


def footer(ctx):
    load_avg = ", ".join(f"{v:.1f}" for v in ctx.get("load_avg", []))
    return (f"\nMeasured on {ctx['num_cpus']} CPUs shared with other work: load average {load_avg} (1, 5, 15 min) when "
            f"the program started on {ctx['date'][:10]}.")


def g(v):
    return f"{v:.3g}"


def ppe(path):
    runs, ctx = load(path)
    sizes = sorted({(k[1], k[2]) for k in runs}, key=lambda s: (s[0], s[1]))
    print("| tank | fluid | unknowns | matrix nonzeros | matrix-free prepare (ms) | Eigen prepare + assembly (ms) "
          "| matrix-free CG solve (ms, iterations) | Eigen CG Jacobi solve (ms, iterations) "
          "| Eigen CG incomplete Cholesky solve (ms, iterations) | matrix-free total (ms) | Eigen Jacobi total (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for dim, side in sizes:
        prep, asm = runs[("BM_Prepare", dim, side, None)], runs[("BM_AssembleEigen", dim, side, None)]
        mf = runs[("BM_SolveMatrixFree", dim, side, None)]
        jac, ic = runs[("BM_SolveEigen", dim, side, 0)], runs[("BM_SolveEigen", dim, side, 1)]
        print(f"| {tank(dim, side)} | {int(prep['fluid'])} | {int(prep['unknowns'])} | {int(asm['nonzeros'])} "
              f"| {g(prep['ms'])} | {g(asm['ms'])} | {g(mf['ms'])} ({int(mf['iterations'])}) "
              f"| {g(jac['ms'])} ({int(jac['iterations'])}) | {g(ic['ms'])} ({int(ic['iterations'])}) "
              f"| {g(prep['ms'] + mf['ms'])} | {g(asm['ms'] + jac['ms'])} |")
    print(footer(ctx))


def step(path):
    runs, ctx = load(path)
    print("| tank | fluid nodes | all nodes | PPE solver | ms per step | steps/s | fluid particle-steps/s |")
    print("|---|---|---|---|---|---|---|")
    for key in sorted(runs, key=lambda k: (k[1], k[2], k[3])):
        b = runs[key]
        solver = "Eigen CG Jacobi" if key[3] else "matrix-free CG"
        print(f"| {tank(key[1], key[2])} | {int(b['fluid'])} | {int(b['nodes'])} | {solver} | {g(b['ms'])} "
              f"| {g(1000 / b['ms'])} | {b['items_per_second']:.3g} |")
    print(footer(ctx))


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("--ppe", "--step"):
        sys.exit(__doc__)
    (ppe if sys.argv[1] == "--ppe" else step)(sys.argv[2])
