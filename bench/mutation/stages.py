# stages.py: the conformance suite in the three stages a mutant runs, in order (bench/mutation.sh):
#   vectors     generated vectors with cycles: `voxcd regress --backends rtl --cycles`, every configuration;
#   directed    the directed cases: the hand-written vector files through `voxcd conform --cycles`, test_rtl's
#               directed tests, the AXI top's directed tests;
#   scoreboard  the random back-pressure scoreboard: test_rtl's random and back-pressure tests, the generated vectors
#               again under random back-pressure (`voxcd regress --stall 0.3`: stalls between a banked slot's read
#               rounds), the AXI top's random handshakes and descriptors.
# Each stage is a list of commands; a command that fails (or runs past its time) kills the mutant.
import os

# test_rtl's tests of each family of models (they iterate the family's models the module offers). Left out: the
# tests that count the build's own model lists (RtlDistance.DirectedCasesOnEveryDistanceModel,
# RtlBanks.DistanceFirstKeepsReadingBehindItsHit, RtlDepth.LatencyAndSquashGrowByOneCyclePerDepth,
# RtlDistance.RandomJobs*, RtlDepth.RandomJobs*), which fail on a module of fewer models (run.py's check of mutant 0).
DIRECTED_RTL = {"lanes": ["Rtl.DirectedCasesOnEveryLaneCount"], "depth": ["RtlDepth.DirectedCasesAtEveryDepth"],
                "sparse": ["RtlSparse.Case*"]}
SCOREBOARD_RTL = {"lanes": ["Rtl.BackPressure*", "Rtl.RandomJobs*"], "depth": ["RtlDepth.BackPressure*"],
                  "distance": ["RtlDistance.BackPressure*"],
                  "banked": ["RtlBanks.BackPressure*", "RtlBanks.RandomJobs*"],
                  "sparse": ["RtlSparse.BackPressure*", "RtlSparse.RandomJobs*"]}
DIRECTED_AXI = ":".join(["*RegistersAfterReset*", "*ErrorResponses*", "*RunOpensTheStream*",
                         "*AddedLatencyIsExact*", "*VectorFiles*", "*MalformedDescriptorsAreRefused*",
                         "*MapAtTheEdgeOfTheLoadedWordsOnEveryAxis*", "*WritesAreRefusedFromADescriptorsFirstBeat*"])
SCOREBOARD_AXI = "*GeneratedVectorsUnderRandomHandshakes*:*RandomDescriptors*"


def vector_commands(voxcd, cfgs, jobs, seeds, stall=None):
    """One `voxcd regress` per lane count, over the device configurations of that lane count (with back-pressure
    when stall is a probability)."""
    by_lanes = {}
    for family, pairs in cfgs:
        if family == "axi":
            continue
        kv = pairs.split()
        lanes = dict(zip(kv[::2], kv[1::2])).get("LANES", "4")
        rest = " ".join(f"{k} {v}" for k, v in zip(kv[::2], kv[1::2]) if k != "LANES") or "default"
        by_lanes.setdefault(lanes, []).append(rest)
    extra = ["--stall", str(stall)] if stall else []
    return [[voxcd, "regress", "--seeds", seeds, "--configs", ";".join(c), "--lanes", lanes, "--backends", "rtl",
             "--jobs-per-shard", str(jobs), "--cycles", *extra] for lanes, c in by_lanes.items()]


def stages(paths, cfgs, jobs=300, seeds="1-2"):
    """[(name, [command, ...])] for the suite over configurations cfgs; paths: voxcd, test_rtl, test_axi, vectors."""
    vec_dir = paths["vectors"]
    hand = sorted(os.path.join(vec_dir, f) for f in os.listdir(vec_dir) if f.endswith(".vec"))
    has_axi = any(f == "axi" for f, _ in cfgs) and paths.get("test_axi")
    families = {f for f, _ in cfgs}
    tests = lambda by_family: ":".join(t for f in by_family if f in families for t in by_family[f])
    directed = [[paths["voxcd"], "conform", *hand, "--backend", "rtl", "--cycles"],
                [paths["test_rtl"], "--gtest_filter=" + tests(DIRECTED_RTL)]]
    scoreboard = [[paths["test_rtl"], "--gtest_filter=" + tests(SCOREBOARD_RTL)],
                  *vector_commands(paths["voxcd"], cfgs, jobs, seeds, stall=0.3)]
    if has_axi:
        directed.append([paths["test_axi"], "--gtest_filter=" + DIRECTED_AXI])
        scoreboard.append([paths["test_axi"], "--gtest_filter=" + SCOREBOARD_AXI])
    return [("vectors", vector_commands(paths["voxcd"], cfgs, jobs, seeds)), ("directed", directed),
            ("scoreboard", scoreboard)]
