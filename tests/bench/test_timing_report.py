"""bench/timing/report.py without the timing tools: the rows and the section of one configuration's run (the default
one with the iCE40 parts, another without them), and their merge into a copy of a table and of a document's
bench:timing block (the rows and the section of the run's configuration and depths replaced, the others kept); then
`report.py merge` run as bench/timing.sh runs it, on fixture files in a temporary directory; and bench/timing.sh's
refusal of a --config it cannot measure.

Usage: python3 test_timing_report.py SOURCE_DIR WORK_DIR
"""
import argparse
import os
import shutil
import subprocess
import sys
import unittest

SOURCE, WORK = sys.argv[1], sys.argv[2]
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(SOURCE, "bench", "timing"))
import report  # noqa: E402

DEFAULT = "-set LANES 4 -set SAW 12 -set MAW 12"
SMALL = "-set LANES 1 -set PW 10 -set PF 2 -set MW 8 -set MF 6 -set TW 20 -set DW 5 -set MEMW 16 -set SAW 8 -set MAW 9 " \
        "-set TAGW 4"
BANKED = DEFAULT.replace("LANES 4", "LANES 16") + " -set BANKS 4"
DEFAULT_TEXT = "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 12 MAW 12 TAGW 16"
SMALL_TEXT = "PW 10 PF 2 MW 8 MF 6 TW 20 DW 5 MEMW 16 LANES 1 SAW 8 MAW 9 TAGW 4"
BANKED_TEXT = "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 16 SAW 12 MAW 12 TAGW 16 BANKS 4"


def args(default, ice40, command="bash bench/timing.sh"):
    return argparse.Namespace(default=default, small=SMALL, ice40=ice40, command=command, goal_mhz=200.0,
                              sram=["2.5", "0.4", "0.1"], wire=["25", "0.2"], fanout="8", secs=["10", "12"],
                              cpu="0m1.0s 0m2.0s", jobs="2", yosys="Yosys 0.23", nextpnr="nextpnr-ice40 0.4",
                              sta_version="2.0.17")


def results(depths, mhz, ice40):
    """What report.py reads from the tools' outputs, made up: `mhz` at every depth."""
    asic = {"wns": -1.0, "mhz": mhz, "start": "a", "end": "b", "area_mm2": 5.0, "groups": [("r[]", 6.5)],
            "cells": 100, "ffs": 10, "buffers": 3, "fanout_before": 40,
            "srams": {"voxcd_sram_64x4096": {"count": 4, "words": 4096, "width": 64}}}
    xilinx = {"luts": 3000, "ffs": 1000, "dsps": 44, "brams": 40, "levels": 8, "carry": 2, "other": {}, "ns": 4.2,
              "mhz": 238.1}
    ice = {"fits": True, "mhz": 60.0, "seeds": [59.0, 60.0, 61.0], "lcs": "4000 / 7680", "lc_used": 4000, "rams": 4,
           "dsps": 0}
    res = {"depths": depths, "asic": {}, "xilinx": {}, "hx8k": {}, "up5k": {}, "up5k_dsp": {}}
    for d in depths:
        res["asic"][d], res["xilinx"][d] = dict(asic), dict(xilinx)
        if ice40:
            res["hx8k"][d], res["up5k"][d], res["up5k_dsp"][d] = dict(ice), dict(ice), [8, 8, 3]
    return res


def read(path):
    with open(path) as f:
        return f.read()


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def rows_of(text):
    return [line.split("\t") for line in text.splitlines() if line and not line.startswith("#")][1:]


def block_of(markdown_text):
    return f"# Doc\n\ntext before\n\n<!-- bench:timing:begin -->\n{markdown_text}<!-- bench:timing:end -->\n\ntext after\n"


class Report(unittest.TestCase):
    def test_the_configuration_text_is_device_configs(self):
        self.assertEqual(report.config_text(DEFAULT), DEFAULT_TEXT)
        self.assertEqual(report.config_text(SMALL), SMALL_TEXT)
        self.assertEqual(report.config_text(BANKED), BANKED_TEXT)
        self.assertEqual(report.config_text(DEFAULT + " -set SB 8"),
                         DEFAULT_TEXT + " SB 8 WB 8", "a distance device's SB and WB, as to_string writes them")
        self.assertEqual(report.same_config("LANES 4 SAW 12 MAW 12"), DEFAULT_TEXT, "defaults for the names not given")
        self.assertEqual(report.lanes_of(BANKED), 16)

    def test_a_run_of_another_configuration_has_its_lanes_and_no_ice40_rows(self):
        text = report.table(args(BANKED, 0), results([0, 1], 90.0, False))
        rows = rows_of(text)
        self.assertEqual([(r[0], r[1]) for r in rows],
                         [("asic-osu018", "0"), ("xilinx-7", "0"), ("asic-osu018", "1"), ("xilinx-7", "1")])
        for r in rows:
            self.assertEqual((r[4], r[11]), ("16", BANKED_TEXT), r)
        self.assertIn(f"# measured: {BANKED_TEXT} by `bash bench/timing.sh` on ", text)
        md = report.markdown(args(BANKED, 0), results([0, 1], 90.0, False))
        self.assertTrue(md.startswith(f"<!-- timing config: {BANKED_TEXT} -->\n#### voxcd_device at LANES 16 SAW 12 "
                                      "MAW 12 BANKS 4\n"), md[:200])
        self.assertNotIn("iCE40", md)
        self.assertIn("Fmax x LANES (16)", md)
        self.assertIn("| 0 | 8 | 90.0 | 5.000 | 288.0 M | 8 (+ 2) |", md, "lookups/s per mm^2 at 16 lanes")

    def test_the_default_run_has_the_ice40_rows_of_the_reduced_configuration(self):
        rows = rows_of(report.table(args(DEFAULT, 1), results([0], 100.4, True)))
        self.assertEqual([(r[0], r[4], r[11]) for r in rows],
                         [("asic-osu018", "4", DEFAULT_TEXT), ("ice40-hx8k", "1", SMALL_TEXT),
                          ("ice40-up5k", "1", SMALL_TEXT), ("xilinx-7", "4", DEFAULT_TEXT)])
        md = report.markdown(args(DEFAULT, 1), results([0], 100.4, True))
        self.assertIn("| depth | latency (cycles) | ASIC Fmax (MHz) | ASIC area (mm^2) | lookups/s per mm^2 | iCE40 HX8K",
                      md)
        self.assertIn("| 0 | 8 | 100.4 |", md)

    def test_merging_replaces_the_runs_rows_and_keeps_the_others(self):
        old = report.table(args(DEFAULT, 1, "old run"), results([0, 1], 100.0, True))
        # Another configuration: added after the others, nothing replaced.
        banked = report.table(args(BANKED, 0, "banked run"), results([0], 90.0, False))
        merged = report.merge_table(old, banked)
        self.assertEqual(rows_of(merged), rows_of(old) + rows_of(banked))
        measured_lines = lambda text: [line for line in text.splitlines() if line.startswith("# measured:")]
        self.assertEqual(measured_lines(merged), measured_lines(old) + measured_lines(banked))
        # The default configuration again at depth 1: its rows there replaced in place, depth 0 and the banked kept.
        again = report.table(args(DEFAULT, 1, "new run"), results([1], 150.0, True))
        merged2 = report.merge_table(merged, again)
        rows = rows_of(merged2)
        self.assertEqual(len(rows), len(rows_of(merged)))
        by_key = {(r[0], r[11], r[1]): r[2] for r in rows}
        self.assertEqual(by_key[("asic-osu018", DEFAULT_TEXT, "1")], "150.0")
        self.assertEqual(by_key[("ice40-hx8k", SMALL_TEXT, "1")], "60.0")
        self.assertEqual(by_key[("asic-osu018", DEFAULT_TEXT, "0")], "100.0", "depth 0 kept")
        self.assertEqual(by_key[("asic-osu018", BANKED_TEXT, "0")], "90.0", "the other configuration kept")
        self.assertEqual([r[:2] for r in rows], [r[:2] for r in rows_of(merged)], "rows keep their places")
        measured = [line for line in merged2.splitlines() if line.startswith("# measured:")]
        self.assertEqual(len(measured), 3, measured)
        self.assertIn(f"# measured: {DEFAULT_TEXT} by `new run` on ", measured[0])
        self.assertIn(f"# measured: {BANKED_TEXT} by `banked run` on ", measured[2])
        # Merging a table into itself changes nothing; a configuration written otherwise is the same one.
        self.assertEqual(report.merge_table(merged2, merged2), merged2)
        short = report.merge_table(merged2, again.replace(DEFAULT_TEXT, "LANES 4 SAW 12 MAW 12"))
        self.assertEqual(len(rows_of(short)), len(rows))
        self.assertEqual([r[11] for r in rows_of(short) if r[0] == "asic-osu018" and r[1] == "1"],
                         ["LANES 4 SAW 12 MAW 12"], "the same configuration, replaced with the run's text")

    def test_merging_the_block_replaces_the_runs_section_and_keeps_the_others(self):
        default = report.markdown(args(DEFAULT, 1, "old run"), results([0], 100.0, True))
        doc = block_of(default)
        banked = report.markdown(args(BANKED, 0, "banked run"), results([0], 90.0, False))
        block = report.merge_block(report.doc_block(doc), banked)
        self.assertEqual(block, default + "\n" + banked)
        again = report.markdown(args(DEFAULT, 1, "new run"), results([0], 150.0, True))
        block2 = report.merge_block(report.doc_block(block_of(block)), again)
        self.assertEqual(block2, again + "\n" + banked, "the default's section replaced in its place")
        self.assertEqual(report.merge_block(report.doc_block(block_of(block2)), banked), block2)
        with self.assertRaises(SystemExit):
            report.doc_block("# a document without the block\n")

    def test_merge_as_timing_sh_runs_it_on_copies(self):
        shutil.rmtree(WORK, ignore_errors=True)
        os.makedirs(WORK)
        path = lambda name: os.path.join(WORK, name)
        old_md = report.markdown(args(DEFAULT, 1, "old run"), results([0, 1], 100.0, True))
        write(path("doc.md"), block_of(old_md))
        write(path("timing.tsv"), report.table(args(DEFAULT, 1, "old run"), results([0, 1], 100.0, True)))
        write(path("run.md"), report.markdown(args(BANKED, 0, "banked run"), results([1], 90.0, False)))
        write(path("run.tsv"), report.table(args(BANKED, 0, "banked run"), results([1], 90.0, False)))
        before = {n: read(path(n)) for n in ("doc.md", "timing.tsv")}
        subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "bench", "timing", "report.py"), "merge",
                        "--run-markdown", path("run.md"), "--run-table", path("run.tsv"), "--doc", path("doc.md"),
                        "--table", path("timing.tsv"), "--out-markdown", path("out.md"), "--out-table",
                        path("out.tsv")], check=True)
        self.assertEqual({n: read(path(n)) for n in ("doc.md", "timing.tsv")}, before, "inputs left alone")
        self.assertEqual(rows_of(read(path("out.tsv"))), rows_of(before["timing.tsv"]) + rows_of(read(path("run.tsv"))))
        self.assertEqual(read(path("out.md")), old_md + "\n" + read(path("run.md")))

    def test_the_source_trees_table_and_block_are_in_the_merged_format(self):
        builtin = read(os.path.join(SOURCE, "host", "device", "timing.tsv"))
        self.assertEqual(report.merge_table(builtin, builtin), builtin, "merged into itself: the same table")
        block = report.doc_block(read(os.path.join(SOURCE, "docs", "hardware.md")))
        head, parts = report.sections(block)
        self.assertEqual(head, [], "every line of the block is in a configuration's section")
        self.assertEqual(parts[0][0], DEFAULT_TEXT, "the default configuration's section first")
        text = "\n".join(block) + "\n"
        self.assertEqual(report.merge_block(block, "\n".join(parts[0][1]) + "\n"), text)

    def test_timing_sh_refuses_a_config_it_cannot_measure(self):
        script = os.path.join(SOURCE, "bench", "timing.sh")
        for config, message in (("DEPTH 2", "give the depth with --depths"),
                                ("FOO 1", "'FOO' is not a configuration parameter"),
                                ("LANES", "is not NAME VALUE pairs"),
                                ("LANES x", "LANES 'x' is not a whole number")):
            r = subprocess.run(["bash", script, "--config", config, "--out", WORK], capture_output=True, text=True)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn(message, r.stderr)


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]], verbosity=2)
