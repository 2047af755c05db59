"""The packed mesh file of fix dem/contact/wall (``lammps.mesh_file``, ``dem-contact lammps-mesh``): a mesh read
back from it packs to the rows the walls room packs from its STL file, bit for bit, with the fix's material
and motion (the hopper of the examples; a floor cut with T-junctions, whose conforming triangles are not the
file's); a file of another version, cut short, altered or not a packed mesh is refused with what to do. (In
LAMMPS, without Python: tests/lammps/test_plugin.py.)"""
import pathlib
import shlex

import numpy as np
import pytest

from dem_contact.errors import InputError
from dem_contact.lammps import mesh_file
from dem_contact.walls import MeshWall, pack, write_stl

ROOT = pathlib.Path(__file__).resolve().parents[2]
MOTION = dict(wall=1, velocity=(0.02, 0.0, -0.01), angular_velocity=(0.0, 0.0, 2.0))


def _t_junctions(path):
    V = np.array([[0, 0, 0], [4, 0, 0], [4, 1, 0], [0, 1, 0], [1, 1, 0], [2, 1, 0], [3, 1, 0], [0, 2, 0],
                  [4, 2, 0]], float) * 1e-2
    T = np.array([[0, 1, 2], [0, 2, 3], [7, 3, 4], [7, 4, 5], [7, 5, 8], [8, 5, 6], [8, 6, 2]])
    write_stl(path, V, T)
    return path


@pytest.mark.parametrize("name", ["hopper", "T-junctions"])
def test_a_packed_mesh_packs_as_its_stl_file(tmp_path, name):
    stl = ROOT / "examples" / "hopper.stl" if name == "hopper" else _t_junctions(tmp_path / "floor.stl")
    scale = 1e-3 if name == "hopper" else 1.0
    path = mesh_file.write(MeshWall.from_stl(stl, scale=scale), tmp_path / "m.mesh")
    for extra in ({}, dict(centre=(0.01, 0.0, 0.0))):
        want_rows, want_mats = pack([MeshWall.from_stl(stl, scale=scale, **MOTION, **extra)], 2)
        got_rows, got_mats = pack([mesh_file.read(path, **MOTION, **extra)], 2)
        assert np.array_equal(got_rows, want_rows) and np.array_equal(got_mats, want_mats)
    if name == "T-junctions":
        assert len(mesh_file.read(path).triangles) > 7           # (the file holds the split triangles)


def test_what_is_not_a_packed_mesh_of_this_version_is_refused(tmp_path):
    stl = _t_junctions(tmp_path / "floor.stl")
    path = mesh_file.write(MeshWall.from_stl(stl), tmp_path / "m.mesh")
    data = pathlib.Path(path).read_bytes()
    head, _, body = data[len(mesh_file.MAGIC):].partition(b"\n")
    first_id = len(data) - len(body) + 8 * (3 + 18)      # (the first payload row's first vertex id)
    cases = {
        "other version": (mesh_file.MAGIC + head.replace(b"version ", b"version 9") + b"\n" + body,
                          "was written by dem_contact 9"),
        "cut short": (data[:-8], "is corrupt (its size)"),
        "no second line": (mesh_file.MAGIC + b"version\n", "is corrupt (its second line)"),
        "a moved vertex": (data[:-8 * 20] + np.float64(0.5).tobytes() + data[-8 * 19:], "does not hold the mesh"),
        "a vertex id not a whole number": (data[:-8 * 10] + np.float64(0.5).tobytes() + data[-8 * 9:],
                                           "is corrupt (its triangles)"),
        "a vertex id beyond any mesh of its triangles": (
            data[:first_id] + np.float64(1e18).tobytes() + data[first_id + 8:], "is corrupt (its triangles)"),
        "fields out of order": (mesh_file.MAGIC + b" ".join(head.split(b" ")[2:4] + head.split(b" ")[:2]
                                                            + head.split(b" ")[4:]) + b"\n" + body,
                                "is corrupt (its second line)"),
        "a count not plain digits": (mesh_file.MAGIC + head.replace(b"keys ", b"keys 0_") + b"\n" + body,
                                     "is corrupt (its second line)"),
    }
    for case, (text, message) in cases.items():
        bad = tmp_path / "bad.mesh"
        bad.write_bytes(text)
        with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
            mesh_file.read(bad)
        assert "dem-contact lammps-mesh" in str(pytest.raises(InputError, mesh_file.read, bad).value), case
    with pytest.raises(InputError, match="is not a packed mesh file"):
        mesh_file.read(stl)
    with pytest.raises(InputError, match="cannot be read"):
        mesh_file.read(tmp_path / "nowhere.mesh")
    assert mesh_file.is_packed(path) and not mesh_file.is_packed(stl) and not mesh_file.is_packed(tmp_path / "no")


def test_the_command_writes_it_and_the_fix_words_read_it(tmp_path, capsys):
    from dem_contact.cli import main
    from dem_contact.lammps.wall_kernel import fix_words, parse

    stl = _t_junctions(tmp_path / "floor.stl")
    out = tmp_path / "floor.mesh"
    assert main(["lammps-mesh", str(stl), "--out", str(out), "--scale", "2"]) == 0
    assert "mesh " + str(out) in capsys.readouterr().out
    wall, slots = parse(["mesh", str(out), "wall", "1", "velocity", "0.02", "0", "-0.01", "angular_velocity", "0",
                         "0", "2"])
    want = pack([MeshWall.from_stl(stl, scale=2.0, **MOTION)])[0]
    assert np.array_equal(pack([wall])[0], want) and slots is None
    # (and the words written for the wall, with slots, read back as the wall and the slots: split as LAMMPS
    # splits a command, quotes removed)
    wall, slots = parse(shlex.split(fix_words(wall, str(out), 3)))
    assert np.array_equal(pack([wall])[0], want) and slots == 3
    with pytest.raises(InputError, match="scale applies to an STL file"):
        parse(["mesh", str(out), "scale", "2"])
    for args, message in ((["--scale", "0"], "--scale must be finite and > 0"),
                          (["--scale", "nan"], "--scale must be finite and > 0")):
        assert main(["lammps-mesh", str(stl), "--out", str(out), *args]) == 2
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1


def test_vertices_no_triangle_uses_are_left_out(tmp_path):
    """A MeshWall with a vertex no triangle uses (before the others, and the origin a vertex of the mesh) is
    written without it: read back, the same triangles' corners and the same rows but for the vertex ids."""
    v = np.array([[9.0, 9.0, 9.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]) * 1e-2
    t = np.array([[1, 2, 3], [1, 3, 4]])
    got = mesh_file.read(mesh_file.write(MeshWall(v, t), tmp_path / "m.mesh"))
    assert np.array_equal(got.vertices[got.triangles], v[t])
    assert np.array_equal(pack([got])[0], pack([MeshWall(v[1:], t - 1)])[0])
