#!/usr/bin/python3
"""The README's liquid benchmark tables from Google Benchmark's JSON output (--benchmark_out=FILE
--benchmark_out_format=json) of bench/mps_ppe_bench.cpp and bench/mps_step_bench.cpp.

    /usr/bin/python3 studies/seed003/bench_table.py --ppe studies/seed003/results/bench_ppe.json
    /usr/bin/python3 studies/seed003/bench_table.py --step studies/seed003/results/bench_step.json [--before studies/seed003/results/bench_step_before.json]
    /usr/bin/python3 studies/seed003/bench_table.py --multigrid studies/seed003/results/bench_multigrid.json

--multigrid reads bench/ppe_multigrid_bench.cpp's output run with --benchmark_repetitions=3
--benchmark_report_aggregates_only=true: each cell is the median of the three with their standard deviation.

With --before, the step table adds each row's time from an earlier build's run of the same benchmark
(the matrix-free CG that applied the operator from the whole Verlet list stood where the parallel CG is now).

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


def multigrid(path):
    data = json.loads(open(path).read())
    cells = {}
    for b in data["benchmarks"]:
        if b.get("run_type") != "aggregate" or b.get("aggregate_name") not in ("median", "stddev"):
            continue
        name = b["run_name"]
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        cells.setdefault(name, {})[b["aggregate_name"]] = (b["real_time"] * scale, b)
    variants = {"BM_Jacobi": "Jacobi CG"}
    print("| tank | unknowns | preconditioner | cycle | Jacobi sweeps | coarse correction scale | finest cubes (l0) "
          "| levels | iterations | solve (ms, median ± sd of 3) | Jacobi CG / this |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    jacobi = {}
    for name, agg in cells.items():
        args = dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", name))
        if name.startswith("BM_Jacobi"):
            jacobi[(args["dim"], args["side"])] = agg["median"][0]
    def order(item):
        args = dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", item[0]))
        return (args["dim"], args["side"], not item[0].startswith("BM_Jacobi"))
    for name, agg in sorted(cells.items(), key=order):
        args = dict((k, int(v)) for k, v in re.findall(r"(\w+):(\d+)", name))
        ms, b = agg["median"]
        sd = agg["stddev"][0]
        ref = jacobi[(args["dim"], args["side"])]
        if name.startswith("BM_Jacobi"):
            setting = "| Jacobi | — | — | — | — | — "
        else:
            setting = (f"| multigrid | {'W' if args['cycle'] == 2 else 'V'} | {args['sweeps']} | {args['scale10'] / 10:g} "
                       f"| {args['agg10'] / 10:g} | {int(b['levels'])} ")
        print(f"| {tank(args['dim'], args['side'])} | {int(b['unknowns'])} {setting}| {int(b['iterations'])} "
              f"| {g(ms)} ± {g(sd)} | {ref / ms:.2f} |")
    print(footer(data["context"]))


def ppe(path):
    runs, ctx = load(path)
    sizes = sorted({(k[1], k[2]) for k in runs}, key=lambda s: (s[0], s[1]))
    print("| tank | fluid | unknowns | matrix nonzeros | prepare (ms) | prepare + compact couplings (ms) "
          "| prepare + Eigen assembly (ms) | parallel CG solve (ms, iterations) | Eigen CG Jacobi solve (ms, iterations) "
          "| Eigen CG incomplete Cholesky solve (ms, iterations) | parallel CG total (ms) | Eigen Jacobi total (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for dim, side in sizes:
        prep, asm = runs[("BM_Prepare", dim, side, None)], runs[("BM_AssembleEigen", dim, side, None)]
        comp, par = runs[("BM_CompactParallel", dim, side, None)], runs[("BM_SolveParallel", dim, side, None)]
        jac, ic = runs[("BM_SolveEigen", dim, side, 0)], runs[("BM_SolveEigen", dim, side, 1)]
        print(f"| {tank(dim, side)} | {int(prep['fluid'])} | {int(prep['unknowns'])} | {int(asm['nonzeros'])} "
              f"| {g(prep['ms'])} | {g(comp['ms'])} | {g(asm['ms'])} | {g(par['ms'])} ({int(par['iterations'])}) "
              f"| {g(jac['ms'])} ({int(jac['iterations'])}) | {g(ic['ms'])} ({int(ic['iterations'])}) "
              f"| {g(comp['ms'] + par['ms'])} | {g(asm['ms'] + jac['ms'])} |")
    print(footer(ctx))


def step(path, before=None):
    runs, ctx = load(path)
    old = load(before)[0] if before else {}
    head = "| tank | fluid nodes | all nodes | PPE solver | ms per step | steps/s | fluid particle-steps/s " \
           "| PPE share of the step | CG iterations per step |"
    if old:
        head += " before: ms per step (solver) | before / now |"
    print(head)
    print("|---" * (head.count("|") - 1) + "|")
    for key in sorted(runs, key=lambda k: (k[1], k[2], k[3])):
        b = runs[key]
        solver = "Eigen CG Jacobi" if key[3] else "parallel CG"
        row = (f"| {tank(key[1], key[2])} | {int(b['fluid'])} | {int(b['nodes'])} | {solver} | {g(b['ms'])} "
               f"| {g(1000 / b['ms'])} | {b['items_per_second']:.3g} | {b['ppe_share']:.0%} | {b['ppe_iterations']:.0f} |")
        if old:
            o = old[key]
            row += f" {g(o['ms'])} ({'Eigen CG Jacobi' if key[3] else 'matrix-free CG'}) | {o['ms'] / b['ms']:.2f} |"
        print(row)
    print(footer(ctx))


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--multigrid":
        multigrid(sys.argv[2])
        sys.exit(0)
    if len(sys.argv) not in (3, 5) or sys.argv[1] not in ("--ppe", "--step") or \
            (len(sys.argv) == 5 and (sys.argv[1] != "--step" or sys.argv[3] != "--before")):
        sys.exit(__doc__)
    if sys.argv[1] == "--ppe":
        ppe(sys.argv[2])
    else:
        step(sys.argv[2], sys.argv[4] if len(sys.argv) == 5 else None)
