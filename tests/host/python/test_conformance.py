"""voxcd.generate_vectors and voxcd.conform against `voxcd conform`: the same files, the same verdicts."""
import filecmp
import os

import pytest

import voxcd


def test_generate_writes_the_tools_file(cli, tmp_path):
    out = cli("conform", "--generate", "--seed", "5", "--jobs", "30", "--lanes", "2", "-o", tmp_path / "cli.vec")
    got = voxcd.generate_vectors(tmp_path / "py.vec", seed=5, jobs=30, lanes=2)
    assert filecmp.cmp(tmp_path / "py.vec", tmp_path / "cli.vec", shallow=False)
    assert out == (f"wrote {tmp_path / 'cli.vec'}: {got['jobs']} jobs, {got['shell_words']} shell words, "
                   f"{got['map_words']} map words, {got['lookups']} lookups, seed 5\n")
    assert got["jobs"] == 30 and got["lookups"] > 0 and "LANES 2" in got["config"]
    assert not (tmp_path / "py.vec.tmp").exists()


def test_generate_with_a_configuration(cli, tmp_path):
    config = "PW 20 PF 6 MW 16 MF 14"
    cli("conform", "--generate", "--seed", "2", "--jobs", "10", "--config", config, "-o", tmp_path / "cli.vec")
    got = voxcd.generate_vectors(str(tmp_path / "py.vec"), seed=2, jobs=10, config=config)
    assert filecmp.cmp(tmp_path / "py.vec", tmp_path / "cli.vec", shallow=False)
    assert got["config"].startswith("PW 20 PF 6 MW 16 MF 14 ")
    with pytest.raises(ValueError, match=r"^config: invalid device configuration: MEMW = 48 is not a power of two$"):
        voxcd.generate_vectors(tmp_path / "bad.vec", config="MEMW 48")
    assert not (tmp_path / "bad.vec").exists()


def test_a_generated_file_passes_on_every_backend(cli, tmp_path):
    path = tmp_path / "g.vec"
    voxcd.generate_vectors(path, seed=7, jobs=40)
    # The SystemC RTL target runs the file on a lane count it has a model of (ctest sets it from VOXCD_SYSC_LANES).
    sysc_lanes = int(os.environ.get("VOXCD_TEST_SYSC_RTL_LANES", "4"))
    for backend in voxcd.backends():
        lanes = sysc_lanes if backend == "sysc-rtl" else None
        r = voxcd.conform(path, backend=backend, lanes=lanes, cycles=backend in ("ref", "cpu"))
        assert r["ok"] and (r["passed"], r["failed"]) == (1, 0), r
        (res,) = r["results"]
        assert res["error"] == "" and res["jobs"] == 40
        assert res["records"] == res["expected_records"] > 40
    assert cli("conform", path).endswith("1 passed, 0 failed\n")


def test_a_corrupted_file_fails_as_with_the_tool(cli, tmp_path):
    good = tmp_path / "good.vec"
    voxcd.generate_vectors(good, seed=3, jobs=20)
    lines = good.read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("hit "))
    f = lines[k].split()
    f[3] = str(int(f[3]) + 1)  # the hit's voxel x
    lines[k] = " ".join(f)
    bad = tmp_path / "bad.vec"
    bad.write_text("\n".join(lines) + "\n")
    r = voxcd.conform([good, bad])
    assert not r["ok"] and (r["passed"], r["failed"]) == (1, 1)
    assert r["results"][0]["ok"] and not r["results"][1]["ok"]
    error = r["results"][1]["error"]
    assert error.startswith(f"{bad}: ") and f"line {k + 1}" in error
    out = cli("conform", good, bad, expect=1)
    assert f"FAIL {error}\n" in out and out.endswith("1 passed, 1 failed\n")


def test_malformed_and_missing_files_fail_with_their_reason(cli, tmp_path):
    broken = tmp_path / "broken.vec"
    broken.write_text("voxcd-vectors 1\nshell 1\n1 2\n")
    missing = tmp_path / "missing.vec"
    r = voxcd.conform([broken, missing], backend="cpu")
    assert (r["passed"], r["failed"]) == (0, 2)
    assert r["results"][0]["error"].startswith(f"{broken}:3: ")
    assert str(missing) in r["results"][1]["error"]
    out = cli("conform", broken, missing, expect=1)
    for res in r["results"]:
        assert f"FAIL {res['error']}\n" in out
