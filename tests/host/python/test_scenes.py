"""voxcd.simulate and voxcd.size against `voxcd simulate --json` and `voxcd size --json`: the same numbers, the same
state hash."""
import json

import pytest

import voxcd

# Host times differ from run to run; everything else is deterministic.
TIMES = {"seconds", "frame_rate_hz", "stage_seconds"}
# The source of the clock of the default configuration's rates when no clock is given (docs/hardware.md, "The default
# clock"), and of a configuration it was not measured for: an estimate from it.
DEFAULT_SOURCE = "OpenSTA, OSU 0.18 um, measured for LANES 4 DEPTH 0, docs/hardware.md"
ESTIMATE_SOURCE = "estimate: the clock of LANES 4 DEPTH 0 (OpenSTA, OSU 0.18 um), not measured for"


def assert_same_summary(got, want):
    assert set(got) == set(want)
    for key, value in want.items():
        if key in TIMES:
            continue
        if key == "clock_source" and value == "given by --clock":
            # The same clock, given by the module's argument instead of the tool's option.
            assert got[key] == "given by the clock argument"
            continue
        if key == "voxmap":
            assert list(got[key]) == value
        elif key == "types":
            assert [t["name"] for t in got[key]] == [t["name"] for t in value]
            assert [t["shell_count"] for t in got[key]] == [t["shell_count"] for t in value]
            assert [t["shell_points"] for t in got[key]] == [t["shell_points"] for t in value]
            assert [t["voxel"] for t in got[key]] == pytest.approx([t["voxel"] for t in value], rel=1e-5)
        elif isinstance(value, float) or isinstance(got[key], float):
            # The tool prints 6 significant digits.
            assert got[key] == pytest.approx(value, rel=1e-5), key
        else:
            assert got[key] == value, key
    assert got["stage_seconds"].keys() == want["stage_seconds"].keys()
    assert got["seconds"] == pytest.approx(sum(got["stage_seconds"].values()), rel=1e-9)


def test_the_default_scene(cli_json):
    want = cli_json("simulate", "--frames", "20")
    got = voxcd.simulate(frames=20)
    assert_same_summary(got, want)
    assert got["state_hash"] == want["state_hash"] == "de188b9acc918936"
    assert got["objects"] == 64 and got["pairs_tested"] > 0 and got["device_cycles"] > 0


def test_a_scene_file(cli_json, scenes):
    want = cli_json("simulate", scenes / "mixed.json", "--frames", "10")
    got = voxcd.simulate(scenes / "mixed.json", frames=10)
    assert_same_summary(got, want)
    assert got["state_hash"] == want["state_hash"]
    assert got["scene"] == str(scenes / "mixed.json") and len(got["types"]) == 3


def test_options_override_the_file_as_the_tools_do(cli_json, scenes):
    want = cli_json("simulate", scenes / "small.json", "--frames", "6", "--seed", "11", "--mode", "FIRST", "--both",
                    "--broadphase", "sap", "--lanes", "2", "--backend", "ref", "--speed", "0.2", "--clock", "150")
    got = voxcd.simulate(str(scenes / "small.json"), frames=6, seed=11, mode="FIRST", both_directions=True, broadphase="sap",
                         lanes=2, backend="ref", speed=0.2, clock=150)
    assert_same_summary(got, want)
    assert (got["mode"], got["broadphase"], got["lanes"], got["clock_mhz"]) == ("FIRST", "sap", 2, 150)
    assert (got["clock_source"], got["clock_estimate"]) == ("given by the clock argument", False)


def test_every_rate_names_its_clock(cli_json, scenes):
    default = voxcd.simulate(frames=5)
    mhz = cli_json("simulate", "--frames", "1")["clock_mhz"]  # the tool's default, the same figure
    assert (default["clock_mhz"], default["clock_source"], default["clock_estimate"]) == (mhz, DEFAULT_SOURCE, False)
    assert default["device_frame_rate_hz"] == pytest.approx(mhz * 1e6 / default["device_cycles_per_frame"])
    given = voxcd.simulate(scenes / "small.json", frames=5)
    assert given["clock_mhz"] == 100 and given["clock_source"] == f"given by {scenes / 'small.json'}'s \"clock\""
    wide = voxcd.simulate(objects=8, frames=2, lanes=32)
    assert (wide["clock_mhz"], wide["clock_source"], wide["clock_estimate"]) == (
        mhz, f"{ESTIMATE_SOURCE} LANES 32, docs/hardware.md", True)
    assert voxcd.simulate(objects=8, frames=2, lanes=32, clock=90)["clock_source"] == "given by the clock argument"
    sized = voxcd.size(scenes / "small.json", frames=5, clock=80)
    assert (sized["clock_mhz"], sized["clock_source"], sized["clock_estimate"]) == (80, "given by the clock argument",
                                                                                     False)
    assert sized["target"] is None and sized["depth_choice"] is None and sized["latency_cycles"] == 8


def test_size_chooses_the_depth_for_a_target(cli_json, scenes):
    want = cli_json("size", scenes / "small.json", "--frames", "5", "--clock", "20", "--target", "ice40-hx8k")
    got = voxcd.size(scenes / "small.json", frames=5, clock=20, target="ice40-hx8k")
    assert got["depth_choice"] == want["depth_choice"] and got["depth_choice"]["depth"] == 0
    assert got["depth_choice"]["why"].startswith("depth 0: ") and got["target"] == "ice40-hx8k"
    with pytest.raises(ValueError, match="target: 'ice40-hx9k' is not one of asic-osu018"):
        voxcd.size(scenes / "small.json", frames=5, target="ice40-hx9k")
    with pytest.raises(ValueError, match="cannot be met: clock: no depth meets 100000 MHz on xilinx-7"):
        voxcd.size(scenes / "small.json", frames=5, clock=100000, target="xilinx-7")


def test_frames_without_device_cycles_have_no_device_rate():
    got = voxcd.simulate(objects=2, density=0.00001, frames=3)
    assert got["device_cycles"] == 0 and got["device_idle_frames"] == 3
    assert got["device_frame_rate_hz"] is None


@pytest.mark.parametrize("clock", [0, -5, float("nan"), float("inf")])
def test_a_clock_that_is_no_frequency_is_refused(scenes, clock):
    with pytest.raises(ValueError, match=r"^clock: .* is not a positive number of MHz$"):
        voxcd.simulate(frames=1, clock=clock)
    with pytest.raises(ValueError, match=r"^clock: .* is not a positive number of MHz$"):
        voxcd.size(scenes / "small.json", frames=1, clock=clock)


def test_a_whole_configuration(cli_json, scenes):
    config = "PW 20 PF 1 MW 16 MF 14 TW 40 DW 8 MEMW 64 LANES 2 SAW 14 MAW 12"
    want = cli_json("simulate", scenes / "small.json", "--frames", "5", "--config", config)
    got = voxcd.simulate(scenes / "small.json", frames=5, config=config)
    assert_same_summary(got, want)
    assert got["device"].startswith(config)


def test_the_built_in_scene_with_options(cli_json):
    want = cli_json("simulate", "--objects", "40", "--shape", "torus", "--resolution", "12", "--density", "0.02",
                    "--frames", "5", "--seed", "3")
    got = voxcd.simulate(objects=40, shape="torus", resolution=12, density=0.02, frames=5, seed=3)
    assert_same_summary(got, want)
    assert got["shape"] == "torus" and got["objects"] == 40


def test_a_scene_as_a_dict_is_the_file(scenes):
    text = json.loads((scenes / "mixed.json").read_text())
    from_dict = voxcd.simulate(text, frames=4)
    from_file = voxcd.simulate(scenes / "mixed.json", frames=4)
    assert from_dict["state_hash"] == from_file["state_hash"]
    assert from_dict["scene"] == "scene" and from_dict["lookups"] == from_file["lookups"]
    with pytest.raises(ValueError, match=r"^scene: types\[0\]\.sise: unknown key"):
        voxcd.simulate({"types": [{"shape": "cube", "sise": 2}]})


def test_size_equals_the_tool(cli_json, scenes):
    want = cli_json("size", scenes / "mixed.json")
    got = voxcd.size(scenes / "mixed.json")
    assert got == want
    assert got["config_text"].startswith("PW ")
    want = cli_json("size", scenes / "small.json", "--accuracy", "0.05", "--rate", "500", "--frames", "20")
    assert voxcd.size(str(scenes / "small.json"), accuracy=0.05, rate=500, frames=20) == want


def test_size_chooses_voxmaps_for_a_contact_accuracy(cli_json, scenes):
    want = cli_json("size", scenes / "mixed.json", "--contact-accuracy", "0.3", "--frames", "5")
    got = voxcd.size(scenes / "mixed.json", contact_accuracy=0.3, frames=5)
    assert got == want
    assert got["contact"]["requested"] == 0.3 and got["contact"]["bound"] <= 0.3
    assert got["config"]["SB"] == got["contact"]["voxmap"]["SB"] > 2
    plain = voxcd.size(scenes / "mixed.json", frames=5)
    assert plain["config"]["SB"] == 2 and plain["contact"]["requested"] is None
    with pytest.raises(ValueError, match=r"mixed\.json: cannot be met: contact: type star \(not convex\)"):
        voxcd.size(scenes / "mixed.json", contact_accuracy=0.1, frames=5)
    with pytest.raises(ValueError, match=r"contact_accuracy: "):
        voxcd.size(scenes / "mixed.json", contact_accuracy=-1)


def test_size_that_cannot_be_met(cli, scenes):
    out = cli("size", scenes / "mixed.json", "--accuracy", "1e-12", expect=3)
    assert out == ""
    with pytest.raises(ValueError, match=r"mixed\.json: cannot be met: accuracy: "):
        voxcd.size(scenes / "mixed.json", accuracy=1e-12)


def test_distance_voxmaps_and_continuous_collision_equal_the_tool(cli_json, scenes):
    want = cli_json("simulate", "--frames", "10", "--distance-bits", "8", "--ccd")
    got = voxcd.simulate(frames=10, distance_bits=8, ccd=True)
    assert_same_summary(got, want)
    assert got["state_hash"] == want["state_hash"]
    assert (got["distance_bits"], got["band"], got["margin"], got["ccd"]) == (8, 4.0, 0.0, True)
    assert got["no_tunnelling"] == want["no_tunnelling"]
    assert set(got["no_tunnelling"]) == {"iterations", "queries", "pairs_limited", "time_of_impact_events",
                                         "bodies_dropped", "lookups"}
    assert got["no_tunnelling"]["iterations"] > 0 and got["no_tunnelling"]["lookups"] > 0
    assert got["device"].endswith("SB 8 WB 8")

    args = ["--frames", "30", "--distance-bits", "16", "--band", "5", "--margin", "0.02", "--ccd"]
    want = cli_json("simulate", scenes / "small.json", *args)
    got = voxcd.simulate(scenes / "small.json", frames=30, distance_bits=16, band=5, margin=0.02, ccd=True)
    assert_same_summary(got, want)
    assert got["state_hash"] == want["state_hash"]
    assert (got["distance_bits"], got["band"], got["margin"]) == (16, 5.0, 0.02)


def test_the_distance_keywords_are_not_ignored(scenes):
    runs = [dict(), dict(distance_bits=8), dict(distance_bits=8, band=6), dict(distance_bits=8, margin=0.05),
            dict(distance_bits=8, ccd=True), dict(distance_bits=4, ccd=True)]
    summaries = [voxcd.simulate(scenes / "small.json", frames=30, **kw) for kw in runs]
    assert len({s["state_hash"] for s in summaries}) == len(runs)
    assert "distance_bits" not in summaries[0] and "no_tunnelling" not in summaries[0]
    assert all("no_tunnelling" not in s for s in summaries[1:4])
    assert [s["band"] for s in summaries[1:]] == [4, 6, 4, 4, 4]
    assert summaries[3]["margin"] == 0.05 and summaries[-1]["distance_bits"] == 4


def test_a_scene_files_distance_keys_and_the_options_over_them(cli_json, tmp_path, scenes):
    text = json.loads((scenes / "small.json").read_text())
    text.update(distance_bits=8, band=5, ccd=True)
    text["types"][1]["mesh"] = str(scenes / "tetra.obj")
    scene = tmp_path / "ccd.json"
    scene.write_text(json.dumps(text))
    want = cli_json("simulate", scene, "--frames", "20")
    got = voxcd.simulate(scene, frames=20)
    assert_same_summary(got, want)
    assert (got["distance_bits"], got["band"], got["ccd"]) == (8, 5.0, True) and "no_tunnelling" in got
    assert voxcd.simulate(text, frames=20)["state_hash"] == got["state_hash"]

    # The options override the file, as the tool's do.
    want = cli_json("simulate", scene, "--frames", "20", "--distance-bits", "4", "--band", "3", "--margin", "0.01")
    got = voxcd.simulate(scene, frames=20, distance_bits=4, band=3, margin=0.01)
    assert_same_summary(got, want)
    assert (got["distance_bits"], got["band"], got["margin"], got["ccd"]) == (4, 3.0, 0.01, True)
    # ccd=False turns the file's "ccd" off (the tool's --ccd only turns it on): the run of the file without the key.
    del text["ccd"]
    (tmp_path / "no-ccd.json").write_text(json.dumps(text))
    want = cli_json("simulate", tmp_path / "no-ccd.json", "--frames", "20")
    got = voxcd.simulate(scene, frames=20, ccd=False)
    assert got["ccd"] is False and "no_tunnelling" not in got and "no_tunnelling" not in want
    assert got["state_hash"] == want["state_hash"] and got["lookups"] == want["lookups"]


def test_bad_distance_keywords_are_refused_as_the_tool_refuses_them(cli_error):
    message = cli_error("simulate", "--frames", "1", "--ccd", expect=105)
    assert message.startswith("--ccd: continuous collision bounds each step by the distance fields")
    with pytest.raises(ValueError) as e:
        voxcd.simulate(frames=1, ccd=True)
    assert str(e.value) == message.removeprefix("--")
    cli_error("simulate", "--frames", "1", "--distance-bits", "3", expect=105)
    with pytest.raises(ValueError, match=r"^distance_bits: 3 is not 4, 8 or 16$"):
        voxcd.simulate(frames=1, distance_bits=3)
    cli_error("simulate", "--frames", "1", "--distance-bits", "8", "--band", "0", expect=105)
    with pytest.raises(ValueError, match=r"^band: must be a positive number of voxels$"):
        voxcd.simulate(frames=1, distance_bits=8, band=0)
    with pytest.raises(ValueError, match=r"^margin: must be a finite number$"):
        voxcd.simulate(frames=1, distance_bits=8, margin=float("inf"))
