"""A small Fig.-3-like sweep on Dask: FE load curves over a grid of (AR, τ_max), one task per
case, each answered by its Result or, when the solver stops short, by its SolveError (reason
and converged part): one diverging case does not stop the sweep.

On this machine (a LocalCluster of worker processes):

    python python/examples/dask_sweep.py --workers 2

On a cluster of many machines, the same code, given the address of a running Dask scheduler
(start one with `dask scheduler` on one node and `dask worker tcp://HEAD:8786` on each node, or
through dask-jobqueue / dask-kubernetes), with wavy installed on every worker:

    python python/examples/dask_sweep.py --scheduler tcp://HEAD:8786

`make test` runs it at a cheap size (python/tests/test_sweeps.py).
"""

from __future__ import annotations

import argparse
import itertools
import time

from dask.distributed import Client, LocalCluster

import wavy


def solve_case(ar: float, tau_max_mpa: float, mesh: str, until: float):
    """One case of the sweep; the failure of a case is its answer, not the sweep's."""
    try:
        return wavy.solve(ar=ar, tau_max_mpa=tau_max_mpa, mesh=mesh, until_a_over_lambda=until)
    except wavy.SolveError as e:
        return e


def describe(ar: float, tau_max_mpa: float, answer) -> str:
    """One line per case: the last point of a curve, or why it stopped and where."""
    case = f"ar={ar} tau_max_mpa={tau_max_mpa}"
    if isinstance(answer, wavy.SolveError):
        return (f"{case}: stopped after {answer.partial.load_steps} load steps"
                f" (a/λ = {answer.a_over_lambda}): {answer.reason}")
    return (f"{case}: {answer.load_steps} load steps, a/λ = {answer.a_over_lambda[-1]:.4f},"
            f" p̄/E* = {answer.p_over_estar[-1]:.6g}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g."
                        " tcp://head:8786; without it a LocalCluster on this machine")
    parser.add_argument("--workers", type=int, default=2,
                        help="worker processes of the LocalCluster (default 2)")
    parser.add_argument("--ar", type=float, nargs="+", default=[0.1, 0.18, 0.3])
    parser.add_argument("--tau-max-mpa", type=float, nargs="+", default=[0.0, 0.1, 0.2])
    parser.add_argument("--mesh", default="coarse", help="as wavy.solve's mesh (default coarse)")
    parser.add_argument("--until-a-over-lambda", type=float, default=0.45)
    args = parser.parse_args(argv)
    cases = list(itertools.product(args.ar, args.tau_max_mpa))
    start = time.perf_counter()
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        # one thread per worker process: a solve uses one core
        client = Client(LocalCluster(n_workers=args.workers, threads_per_worker=1,
                                     processes=True, dashboard_address=None))
    with client:
        futures = [client.submit(solve_case, ar, tau, args.mesh, args.until_a_over_lambda,
                                 pure=False) for ar, tau in cases]
        answers = client.gather(futures)
        client.close()
    failed = 0
    for (ar, tau), answer in zip(cases, answers):
        failed += isinstance(answer, wavy.SolveError)
        print(describe(ar, tau, answer))
    print(f"{len(cases)} cases, {failed} stopped short, {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
