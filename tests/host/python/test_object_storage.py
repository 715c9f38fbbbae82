"""voxcd.Object's storage, memory and bricks against `voxcd info --json` of the same object file (dense, sparse and
sparse-with-distance objects), and the distance properties of a field stored sparse."""
import struct
import zlib

import numpy as np
import pytest

import voxcd

# (shape, resolution, --storage, --distance-bits): the forms each stores are asserted below, so that a case that
# stopped storing what it names would fail rather than test the dense path twice.
CASES = {
    "dense": ("torus", 24, "dense", 0),
    "sparse": ("torus", 24, "sparse", 0),
    "auto": ("torus", 24, "auto", 0),
    "sparse_distance": ("cube", 24, "sparse", 8),
    "dense_distance": ("cube", 24, "dense", 8),
}
STORED = {
    "dense": {"voxmap": "dense", "shell": "dense", "distance": None},
    "sparse": {"voxmap": "sparse", "shell": "sparse", "distance": None},
    "auto": {"voxmap": "dense", "shell": "sparse", "distance": None},
    "sparse_distance": {"voxmap": "dense", "shell": "dense", "distance": "sparse"},
    "dense_distance": {"voxmap": "dense", "shell": "dense", "distance": "dense"},
}


def made_by_the_tool(cli_json, tmp_path, case):
    shape, resolution, storage, bits = CASES[case]
    path = tmp_path / (case + ".vxo")
    opts = ["--distance-bits", bits] if bits else []
    info = cli_json("voxelize", shape, "--resolution", resolution, "--storage", storage, *opts, "-o", path)
    return path, info


def expected_memory(info):
    """Object.memory as `voxcd info --json` gives its figures."""
    dense, sparse = info["storage"]["dense"], info["storage"]["sparse"]
    memory = {
        "voxmap": {"stored": info["voxmap_bytes"], "dense": dense["voxmap_bytes"], "sparse": sparse["voxmap_bytes"]},
        "shell": {"stored": info["shell_bytes"], "dense": dense["shell_bytes"],
                  "sparse": sparse["shell_bytes"] if "shell_words" in sparse else None},
        "distance": None,
    }
    f = info.get("distance")
    if f:
        is_sparse = f["storage"] == "sparse"
        memory["distance"] = {"stored": f["memory_bytes"],
                              "dense": f["dense_memory_bytes"] if is_sparse else f["memory_bytes"],
                              "sparse": f["memory_bytes"] if is_sparse else None}
    return memory


def expected_bricks(info):
    sparse, f = info["storage"]["sparse"], info.get("distance")
    levels = tuple(f["bricks_per_level"]) if f and f["storage"] == "sparse" else None
    return {"voxmap": sparse["cells"]["brick"], "shell": sparse.get("shell_bricks"), "distance": levels,
            "distance_refined": sum(levels[1:]) if levels else None}


@pytest.mark.parametrize("case", list(CASES))
def test_storage_memory_and_bricks_are_voxcd_infos(cli_json, tmp_path, case):
    path, info = made_by_the_tool(cli_json, tmp_path, case)
    shape, resolution, storage, bits = CASES[case]
    made = voxcd.voxelize(shape, resolution=resolution, storage=storage, distance_bits=bits)
    for obj in (voxcd.read_object(path), made):
        assert obj.storage == STORED[case]
        assert obj.storage["voxmap"] == info["storage"]["voxmap"] and obj.storage["shell"] == info["storage"]["shell"]
        assert obj.storage["distance"] == (info["distance"]["storage"] if "distance" in info else None)
        assert obj.memory == expected_memory(info)
        assert obj.bricks == expected_bricks(info)
        sparse = [part for part in ("voxmap", "shell", "distance") if obj.storage[part] == "sparse"]
        assert repr(obj).endswith(("; sparse: " + ", ".join(sparse) if sparse else "") + ">"), repr(obj)
        assert ("-bit distance field" in repr(obj)) == bool(bits)


def test_the_other_forms_figures_do_not_depend_on_the_form_stored(cli_json, tmp_path):
    dense = voxcd.read_object(made_by_the_tool(cli_json, tmp_path, "dense")[0])
    sparse = voxcd.read_object(made_by_the_tool(cli_json, tmp_path, "sparse")[0])
    for part in ("voxmap", "shell"):
        assert dense.memory[part]["stored"] == dense.memory[part]["dense"]
        assert sparse.memory[part]["stored"] == sparse.memory[part]["sparse"]
        assert {k: dense.memory[part][k] for k in ("dense", "sparse")} == \
               {k: sparse.memory[part][k] for k in ("dense", "sparse")}
    assert dense.bricks == sparse.bricks and dense.bricks["voxmap"] > 0 and dense.bricks["shell"] > 0
    # The torus at 24 voxels across is small: its sparse voxmap (table and 128-byte bricks) is larger than the dense
    # one, its sparse shell smaller.
    assert sparse.memory["voxmap"]["sparse"] > sparse.memory["voxmap"]["dense"]
    assert sparse.memory["shell"]["sparse"] < sparse.memory["shell"]["dense"]


def test_a_sparse_field_reads_as_the_dense_one(cli_json, tmp_path):
    path, info = made_by_the_tool(cli_json, tmp_path, "sparse_distance")
    obj = voxcd.read_object(path)
    dense = voxcd.voxelize("cube", resolution=24, distance_bits=8, storage="dense")
    assert obj.distance_bits == info["distance"]["bits"] == 8
    assert obj.distance_step == info["distance"]["step"] == dense.distance_step
    # The cube's edges refine to level 1; the dense field lowers their conservative cells' nodes to 0 instead.
    assert obj.bricks["distance_refined"] > 0 and dense.report["conservative_cells"] > 0
    a, b = obj.distance, dense.distance
    assert a.shape == b.shape == tuple(n + 1 for n in obj.dims) and a.dtype == np.int16 and a.flags["F_CONTIGUOUS"]
    assert np.all((a == b) | ((b == 0) & (a > 0)))


def test_a_torus_field_is_the_same_stored_either_way():
    sparse = voxcd.voxelize("torus", resolution=24, distance_bits=8, storage="sparse")
    dense = voxcd.voxelize("torus", resolution=24, distance_bits=8, storage="dense")
    assert sparse.storage["distance"] == "sparse" and dense.storage["distance"] == "dense"
    np.testing.assert_array_equal(sparse.distance, dense.distance)


def with_an_empty_sparse_field(data, dims, bits=8):
    """An object file (version 5) given a sparse distance field whose every cell is uniform far outside: the sparse
    distance section (docs/objects.md, "Sparse distance field") in place of the empty one, the flag, the checksum."""
    cells = 1
    for n in dims:
        cells *= -(-n // 8)
    field = struct.pack("<Id3IIQ", bits, 4.0 / 2 ** (bits - 1), *dims, 8, cells) + bytes(-(-cells // 2)) + \
        struct.pack("<QQ", 0, 0)
    body = data[:-4]
    assert body[-12:] == struct.pack("<IQ", 0, 0), "the file ends with an absent sparse distance section"
    body = body[:12] + struct.pack("<I", struct.unpack_from("<I", body, 12)[0] | 8) + body[16:-12]
    body += struct.pack("<IQ", 1, len(field)) + field
    return body + struct.pack("<I", zlib.crc32(body))


def test_a_sparse_field_too_large_for_a_dense_array(cli_json, tmp_path):
    # A rod 1,033 voxels long: its voxmap is sparse (no dense voxmap is that long), and so is the field given to it.
    (tmp_path / "rod.obj").write_text("v 0 0 0\nv 100 0 0\nv 0 1 0\nv 100 1 0\nv 0 0 1\nv 100 0 1\nv 0 1 1\n"
                                      "v 100 1 1\nf 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
                                      "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n")
    path = tmp_path / "rod.vxo"
    rod = cli_json("voxelize", tmp_path / "rod.obj", "--resolution", "1030", "--storage", "sparse", "-o", path)
    assert rod["dims"][0] > 1024 and rod["storage"]["voxmap"] == "sparse"
    path.write_bytes(with_an_empty_sparse_field(path.read_bytes(), rod["dims"]))
    info = cli_json("info", path)
    obj = voxcd.read_object(path)
    assert obj.storage == {"voxmap": "sparse", "shell": "sparse", "distance": "sparse"}
    assert obj.distance_bits == 8 and obj.distance_step == 4.0 / 128
    assert obj.memory == expected_memory(info) and obj.bricks == expected_bricks(info)
    assert obj.bricks["distance"] == (0, 0, 0, 0)
    with pytest.raises(ValueError, match=r"distance field is stored sparse on a grid of 1033x\d+x\d+ voxels, larger "
                                         r"than a dense field's 1024 per axis: it has no dense array"):
        obj.distance
    with pytest.raises(ValueError, match=r"voxmap is stored sparse and is larger than 1024"):
        obj.states
