#!/usr/bin/env python3
"""Branin and Hartmann-6 through `dcs study ask/tell`, against Optuna 4.9's TPESampler.

For each sampler (tpe; tpe_mvg, TPE with --multivariate --group; random) and problem, SEEDS studies of TRIALS sequential trials, each
asked and told through the `dcs` client on a local --store file, as a user outside DCS would.
Prints, per sampler, problem and checkpoint trial (10, 25, 50, 100), the median best-so-far over
the seeds with its 90 % percentile-bootstrap interval (2000 resamples), q25/q75 (linear
interpolation) and the mean, beside Optuna 4.9.0's median and 90 % interval for the same sampler
(OPTUNA below), and the wall time per ask + tell.

Usage: bench/study/ask_tell.py [--seeds 20] [--trials 100] [--samplers tpe,tpe_mvg,random]
       [--dcs build/services/dcs]
"""
import argparse
import json
import math
import os
import random
import statistics
import subprocess
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# Optuna 4.9.0's TPESampler, 20 seeds: (median, CI low, CI high) of Optuna's best-so-far at each
# trial.
OPTUNA = {
    ("branin", "tpe_mvg"): {10: (5.80074, 3.46402, 8.26807), 25: (0.851146, 0.616406, 1.5081),
                            50: (0.540049, 0.509283, 0.583169), 100: (0.48202, 0.421005, 0.513129)},
    ("hartmann6", "tpe_mvg"): {10: (-0.707472, -1.10664, -0.582384),
                               25: (-2.23802, -2.38807, -1.62016),
                               50: (-2.72735, -2.9122, -2.62099), 100: (-3.00403, -3.11436, -2.8669)},
    ("branin", "tpe"): {10: (5.80074, 3.46402, 8.26807), 25: (1.57498, 0.840607, 2.29761),
                        50: (0.824282, 0.591755, 1.09868), 100: (0.447925, 0.428963, 0.489277)},
    ("branin", "random"): {10: (5.80074, 3.46402, 8.26807), 25: (1.86007, 1.00696, 3.89394),
                           50: (1.14442, 0.761396, 1.70473), 100: (0.778, 0.549932, 1.1151)},
    ("hartmann6", "tpe"): {10: (-0.707472, -1.10664, -0.582384), 25: (-1.99402, -2.39345, -1.57464),
                           50: (-2.72228, -2.81646, -2.4797), 100: (-2.99561, -3.10323, -2.84522)},
    ("hartmann6", "random"): {10: (-0.707472, -1.10664, -0.582384),
                              25: (-1.15048, -1.39941, -0.952031),
                              50: (-1.76822, -2.02335, -1.55536),
                              100: (-2.12313, -2.33496, -2.02335)},
}


def branin(p):
    b, c, t = 5.1 / (4 * math.pi ** 2), 5 / math.pi, 1 / (8 * math.pi)
    x1, x2 = p["x1"], p["x2"]
    return (x2 - b * x1 ** 2 + c * x1 - 6) ** 2 + 10 * (1 - t) * math.cos(x1) + 10


HARTMANN_ALPHA = (1.0, 1.2, 3.0, 3.2)
HARTMANN_A = ((10, 3, 17, 3.5, 1.7, 8), (0.05, 10, 17, 0.1, 8, 14), (3, 3.5, 1.7, 10, 17, 8),
              (17, 8, 0.05, 10, 0.1, 14))
HARTMANN_P = ((0.1312, 0.1696, 0.5569, 0.0124, 0.8283, 0.5886),
              (0.2329, 0.4135, 0.8307, 0.3736, 0.1004, 0.9991),
              (0.2348, 0.1451, 0.3522, 0.2883, 0.3047, 0.6650),
              (0.4047, 0.8828, 0.8732, 0.5743, 0.1091, 0.0381))


def hartmann6(p):
    x = [p[f"x{j}"] for j in range(6)]
    return -sum(a * math.exp(-sum(A[j] * (x[j] - P[j]) ** 2 for j in range(6)))
                for a, A, P in zip(HARTMANN_ALPHA, HARTMANN_A, HARTMANN_P))


PROBLEMS = {"branin": branin, "hartmann6": hartmann6}


def dcs(binary, *args):
    return subprocess.run([binary, *args], check=True, capture_output=True, text=True).stdout


def study(binary, store, problem, sampler, seed, trials):
    """The best-so-far after each trial, and the seconds spent in ask + tell."""
    options = {"tpe": ["--sampler", "tpe"], "random": ["--sampler", "random"],
               "tpe_mvg": ["--sampler", "tpe", "--multivariate", "--group"]}[sampler]
    study_id = dcs(binary, "study", "create", "--space", os.path.join(HERE, f"{problem}.yaml"),
                   *options, "--seed", str(seed), "--store", store).strip()
    best, seconds = [], 0.0
    for _ in range(trials):
        start = time.perf_counter()
        trial = json.loads(dcs(binary, "study", "ask", study_id, "--store", store))
        seconds += time.perf_counter() - start
        value = PROBLEMS[problem](trial["params"])
        start = time.perf_counter()
        dcs(binary, "study", "tell", study_id, str(trial["trial"]), repr(value), "--store", store)
        seconds += time.perf_counter() - start
        best.append(value if not best else min(best[-1], value))
    return best, seconds


def quantile(sorted_values, q):
    position = q * (len(sorted_values) - 1)
    low = math.floor(position)
    high = min(low + 1, len(sorted_values) - 1)
    return sorted_values[low] + (sorted_values[high] - sorted_values[low]) * (position - low)


def median_interval(values, rng, resamples=2000):
    medians = sorted(statistics.median(rng.choices(values, k=len(values)))
                     for _ in range(resamples))
    return quantile(medians, 0.05), quantile(medians, 0.95)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--seeds", type=int, default=20)
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--dcs", default="build/services/dcs")
    parser.add_argument("--samplers", default="tpe,tpe_mvg,random")
    args = parser.parse_args()
    rng = random.Random(0)
    print("| problem | sampler | trial | median best | 90 % CI of median | q25 | q75 | mean | "
          "Optuna 4.9, same sampler: median [90 % CI] |")
    print("|---|---|---|---|---|---|---|---|---|")
    timings = []
    with tempfile.TemporaryDirectory() as scratch:
        store = os.path.join(scratch, "studies.db")
        for problem in PROBLEMS:
            for sampler in args.samplers.split(","):
                runs = []
                for seed in range(args.seeds):
                    best, seconds = study(args.dcs, store, problem, sampler, seed, args.trials)
                    runs.append(best)
                    timings.append((sampler, problem, seconds / args.trials))
                for trial in (10, 25, 50, 100):
                    if trial > args.trials:
                        continue
                    values = sorted(run[trial - 1] for run in runs)
                    low, high = median_interval(values, rng)
                    optuna = OPTUNA[(problem, sampler)][trial]
                    print(f"| {problem} | {sampler} | {trial} | {statistics.median(values):.6g} | "
                          f"[{low:.6g}, {high:.6g}] | {quantile(values, 0.25):.6g} | "
                          f"{quantile(values, 0.75):.6g} | {statistics.mean(values):.6g} | "
                          f"{optuna[0]:.6g} [{optuna[1]:.6g}, {optuna[2]:.6g}] |", flush=True)
    for sampler, problem in {(s, p) for s, p, _ in timings}:
        per_trial = [t for s, p, t in timings if s == sampler and p == problem]
        print(f"{problem} {sampler}: {1000 * statistics.mean(per_trial):.1f} ms per ask + tell "
              "(two dcs processes, the store opened by each)")


if __name__ == "__main__":
    main()
