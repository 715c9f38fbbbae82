#!/usr/bin/python3
"""Distributed `voxcd simulate` on this machine and a model that projects it (docs/scale.md).

Runs `voxcd simulate --objects N --threads 1 --json` on 1 process and under `mpirun -np R` (R = 2, and 3
oversubscribed on a 2-core machine), REPEATS times each, interleaved; prints the median frame rate of rank 0 (the
sum of its stage times: it includes waiting for the other ranks), the ratio to one process from the same repeats,
the bytes rank 0 sends and receives per frame, and the state hash of every run (they must agree). Then it fits the
projection model of docs/scale.md to the one-process stage times and the measured traffic and projects N = 10^6
bodies to 16, 64 and 256 ranks, and a 10^9-lookup campaign from `voxcd regress` throughput.

  /usr/bin/python3 bench/scale.py [--build build] [--repeats 3] [--counts 4096,65536] [--frames 200,20]
                                  [--campaign-rate LOOKUPS_PER_S_PER_RANK] [--markdown]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

# The projection's stated assumptions (docs/scale.md, "The model").
LATENCY_S = 2e-6        # one MPI message between nodes (InfiniBand-class network)
BANDWIDTH_BPS = 10e9    # bytes per second into or out of one rank
OUTCOME_BYTES = 64      # one tested pair's outcome (host/scene/exchange.cpp)
CAMPAIGN_SHARD_S = 1e-4  # rank 0's time to receive, record and hand out one shard (fsync'd results line excluded)


def run(build, n, frames, ranks):
    cmd = [os.path.join(build, "voxcd"), "simulate", "--objects", str(n), "--frames", str(frames), "--threads", "1",
           "--json"]
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)] + cmd
    out = subprocess.run(cmd, env=ENV, check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def measure(build, counts, frames, repeats):
    rows = []
    for n, f in zip(counts, frames):
        runs = {1: [], 2: [], 3: []}
        for _ in range(repeats):
            for r in (1, 2, 3):  # interleaved: the machine's load drifts
                runs[r].append(run(build, n, f, r))
        hashes = {s["state_hash"] for rs in runs.values() for s in rs}
        if len(hashes) != 1:
            sys.exit(f"scale.py: {n} objects: state hashes differ between ranks: {sorted(hashes)}")
        one = statistics.median(s["frame_rate_hz"] for s in runs[1])
        for r in (1, 2, 3):
            rates = [s["frame_rate_hz"] for s in runs[r]]
            ratios = [a["frame_rate_hz"] / b["frame_rate_hz"] for a, b in zip(runs[r], runs[1])]
            rows.append({
                "objects": n, "frames": f, "ranks": r, "rate": statistics.median(rates),
                "ratio": statistics.median(ratios),
                "bytes": statistics.median(s.get("rank0_bytes_per_frame", 0) for s in runs[r]),
                "tested": runs[r][0]["pairs_tested"] / f, "hash": runs[r][0]["state_hash"],
                "stages": runs[1][0]["stage_seconds"] if r == 1 else None, "one": one,
            })
    return rows


def model(rows, campaign_rate):
    """Per-body costs from the largest one-process run, traffic per tested pair; N = 10^6 at 16, 64, 256 ranks."""
    big = max((r for r in rows if r["ranks"] == 1), key=lambda r: r["objects"])
    n, f, st = big["objects"], big["frames"], big["stages"]
    # Replicated on every rank: integration, bounds, the response. Divided by the ranks: broadphase and pair tests.
    rep = (st["integrate"] + st["bounds"] + st["response"]) / f / n
    div = (st["broadphase"] + st["narrow"]) / f / n
    tested_per_body = big["tested"] / n
    out = {"fit": {"objects": n, "replicated_us_per_body": rep * 1e6, "divided_us_per_body": div * 1e6,
                   "tested_per_body": tested_per_body}, "bodies": [], "campaign": []}
    N = 1e6
    for R in (1, 16, 64, 256):
        compute = N * rep + N * div / R
        outcomes = N * tested_per_body * OUTCOME_BYTES
        # As implemented: every rank sends its share to the R-1 others and receives theirs, R-1 messages each way.
        a2a = (R - 1) * LATENCY_S + (outcomes * (R - 1) / R) / BANDWIDTH_BPS
        # An allgather over a tree (MPI_Allgatherv's algorithms): log2(R) steps, each rank receiving every share once.
        tree = (2 * (R - 1).bit_length()) * LATENCY_S + outcomes / BANDWIDTH_BPS if R > 1 else 0.0
        out["bodies"].append({"ranks": R, "compute_ms": compute * 1e3, "a2a_ms": a2a * 1e3, "tree_ms": tree * 1e3,
                              "a2a_hz": 1 / (compute + a2a), "tree_hz": 1 / (compute + tree),
                              # Were integration and bounds divided too (bodies kept by their slab's rank only):
                              "all_divided_hz": 1 / (N * (rep + div) / R + tree),
                              "speedup_a2a": (N * (rep + div)) / (compute + a2a)})
    if campaign_rate:
        L, shard = 1e9, 200 * 40  # lookups, lookups per shard (200 jobs of about 40 points)
        shards = L / shard
        for R in (1, 16, 64, 256):
            t = L / (R * campaign_rate)
            t0 = shards * CAMPAIGN_SHARD_S  # rank 0's serial share
            out["campaign"].append({"ranks": R, "hours": max(t, t0) / 3600, "rank0_bound": t0 >= t})
    return out


def markdown(rows, m, campaign_rate):
    lines = ["| objects | ranks | frame rate, rank 0 (Hz, median) | / one process (same repeats) | bytes per frame at "
             "rank 0 | pairs tested per frame | state hash |", "|---:|---|---:|---:|---:|---:|---|"]
    for r in rows:
        label = f"{r['ranks']}" + (" (oversubscribed)" if r["ranks"] > (os.cpu_count() or 1) else "")
        lines.append(f"| {r['objects']} | {label} | {r['rate']:.1f} | {r['ratio']:.2f} | {r['bytes']:.0f} | "
                     f"{r['tested']:.0f} | `{r['hash']}` |")
    fit = m["fit"]
    lines += ["", f"Fit (one process, {fit['objects']} objects, one thread): replicated stages "
              f"{fit['replicated_us_per_body']:.3f} us per body and frame, divided stages "
              f"{fit['divided_us_per_body']:.3f} us, {fit['tested_per_body']:.3f} pairs tested per body and frame.",
              "", "| N = 10^6, ranks | compute per frame (ms) | exchange, all-to-all (ms) | exchange, tree (ms) | "
              "frame rate, all-to-all (Hz) | frame rate, tree (Hz) | speed-up over one rank (all-to-all) | every stage divided, "
              "tree (Hz) |", "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for b in m["bodies"]:
        lines.append(f"| {b['ranks']} | {b['compute_ms']:.1f} | {b['a2a_ms']:.2f} | {b['tree_ms']:.2f} | "
                     f"{b['a2a_hz']:.1f} | {b['tree_hz']:.1f} | {b['speedup_a2a']:.1f} | "
                     f"{b['all_divided_hz']:.1f} |")
    if m["campaign"]:
        lines += ["", f"10^9-lookup campaign at {campaign_rate:.3g} lookups/s per rank (`bash bench/regress.sh`):", "",
                  "| ranks | hours | limited by |", "|---:|---:|---|"]
        for c in m["campaign"]:
            lines.append(f"| {c['ranks']} | {c['hours']:.3f} | {'rank 0' if c['rank0_bound'] else 'the ranks'} |")
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default="build")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--counts", default="4096,65536")
    p.add_argument("--frames", default="200,20")
    p.add_argument("--campaign-rate", type=float, default=0)
    p.add_argument("--markdown", action="store_true")
    a = p.parse_args()
    counts = [int(x) for x in a.counts.split(",")]
    frames = [int(x) for x in a.frames.split(",")]
    rows = measure(a.build, counts, frames, a.repeats)
    m = model(rows, a.campaign_rate)
    if a.markdown:
        print(markdown(rows, m, a.campaign_rate))
    else:
        print(json.dumps({"rows": rows, "model": m}, indent=1))


if __name__ == "__main__":
    main()
