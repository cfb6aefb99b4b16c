"""The files `vorball channels` writes, opened by the tools users open them
with (#16, "outputs that the tools open"): the centreline PDB by
Biopython's strict parser and by gemmi, the PyMOL script's paths from its
own folder, the VTK volumes by meshio, the MRC volumes by mrcfile (its
validator too) and gemmi; each checked against the table and the JSON of
the same run (channels, points, radii, grid, origin, voxel size)."""
import csv
import json
import os
import warnings

import numpy as np
import pytest

from conftest import cli, corpus

GRAMICIDIN = corpus("data", "1grm_single_hole2.pdb")
TRAJ = corpus("data", "ngl_md_ascii_trj.pdb")
GRID = 64


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """Two runs on one fixed grid (a run writes one mask volume): the mask as
    MRC with the occupancy as VTK, then the other way round; every other
    output of the first run in a subfolder, so the script's paths are not
    bare names."""
    d = tmp_path_factory.mktemp("outputs")
    (d / "sub").mkdir()
    common = ["--grid", GRID, "--device", "ref", "--fixed-grid", GRAMICIDIN]
    cli("channels", "-o", d / "t.csv", "--stats-file", d / "stats.csv",
        "--centerlines", d / "sub" / "c.pdb", "--pymol", d / "sub" / "c.pml",
        "--volume", d / "m.mrc", "--occupancy", d / "o.vtk", "--profile", d / "p.csv", *common)
    cli("channels", "-o", d / "t.json", "--json", "--volume", d / "m.vtk",
        "--occupancy", d / "o.mrc", *common)
    table = list(csv.DictReader(open(d / "t.csv")))
    stats = list(csv.DictReader(open(d / "stats.csv")))
    frame = json.load(open(d / "t.json"))["frames"][0]
    return d, table, stats[0], frame


def biopython_strict(path):
    """The structure by PDBParser(PERMISSIVE=False), which raises on any
    construction error (duplicate atoms, ...), and the warnings it gave."""
    from Bio.PDB import PDBParser
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        s = PDBParser(PERMISSIVE=False).get_structure("c", str(path))
    return s, [str(x.message) for x in w]


def conect_pairs(path):
    """CONECT pairs of a PDB file; asserts they all come after the last atom."""
    lines = open(path).read().splitlines()
    last_atom = max(k for k, l in enumerate(lines) if l.startswith(("ATOM", "HETATM")))
    pairs = []
    for k, l in enumerate(lines):
        if l.startswith("CONECT"):
            assert k > last_atom, "CONECT before an atom: line %d" % (k + 1)
            pairs.append((int(l[6:11]), int(l[11:16])))
    assert lines[-1] == "END"
    return pairs


def check_biopython_reads(path, table_rows, frames, json_channels=None):
    """One model per frame, one residue per channel holding its points in
    order, with the radius in the B-factor; unknown element 'X' (the only
    warning Biopython gives is that it could not put an element in its
    place); serials unique in a model."""
    s, warned = biopython_strict(path)
    assert all(m.startswith("Could not assign element") for m in warned), set(warned)
    models = list(s)
    assert len(models) == len(frames)
    for m, f in zip(models, frames):
        rows = [r for r in table_rows if int(r["frame"]) == f]
        residues = [r for c in m for r in c]
        assert len(residues) == len(rows)
        serials = [a.serial_number for r in residues for a in r]
        assert serials == list(range(1, len(serials) + 1))
        for k, (res, row) in enumerate(zip(residues, rows)):
            assert res.id[1] == k + 1
            assert res.resname == {"pore": "POR", "channel": "CHN", "cavity": "CAV"}[row["kind"]]
            atoms = list(res)
            assert len(atoms) == int(row["points"])
            assert len({a.get_name() for a in atoms}) == len(atoms)
            assert all(a.element == "X" for a in atoms)
            b = np.array([a.get_bfactor() for a in atoms])
            assert abs(b.min() - float(row["bottleneck_A"])) <= 0.005 + 1e-9
            if json_channels is not None and f == frames[0]:
                pts = np.array(json_channels[k]["centreline"])
                assert np.allclose([a.coord for a in atoms], pts[:, :3], atol=6e-4)
                assert np.allclose(b, pts[:, 3], atol=5e-3 + 1e-9)
    return models


def test_centrelines_pdb_biopython_strict(run):
    d, table, _, frame = run
    assert len(table) >= 5
    check_biopython_reads(d / "sub" / "c.pdb", table, [0], frame["channels"])
    # Bonds join consecutive points of each channel and nothing else.
    pairs = conect_pairs(d / "sub" / "c.pdb")
    assert len(pairs) == sum(int(r["points"]) - 1 for r in table)
    assert all(b == a + 1 for a, b in pairs)


def test_centrelines_pdb_gemmi(run):
    import gemmi
    d, table, _, frame = run
    st = gemmi.read_structure(str(d / "sub" / "c.pdb"))
    assert len(st) == 1
    residues = [r for ch in st[0] for r in ch]
    assert len(residues) == len(table)
    for res, row, c in zip(residues, table, frame["channels"]):
        assert res.seqid.num == int(row["channel"])
        assert len(res) == int(row["points"])
        assert len({a.name for a in res}) == len(res)
        assert all(a.element.name == "X" for a in res)
        pos = np.array([[a.pos.x, a.pos.y, a.pos.z] for a in res])
        assert np.allclose(pos, np.array(c["centreline"])[:, :3], atol=6e-4)


def test_length_is_the_centrelines_length(run):
    """length_A is the length of the polyline through the written points, for
    the pore and for the channels whose bottleneck points were moved off the
    voxel centres (to the JSON's 3 decimals: each segment within 2e-3)."""
    _, table, _, frame = run
    assert [c["kind"] for c in frame["channels"]] == [r["kind"] for r in table]
    for c, row in zip(frame["channels"], table):
        p = np.array(c["centreline"])[:, :3]
        length = np.linalg.norm(np.diff(p, axis=0), axis=1).sum()
        assert abs(length - c["length_A"]) <= 2e-3 * len(p), (c["id"], length, c["length_A"])
        assert "%.3f" % c["length_A"] == row["length_A"]


def test_trajectory_centrelines_one_model_per_frame(tmp_path):
    import gemmi
    cli("channels", "--no-pore", "--grid", GRID, "--device", "ref", "--frames", "0:3",
        "-o", tmp_path / "t.csv", "--centerlines", tmp_path / "c.pdb", TRAJ)
    table = list(csv.DictReader(open(tmp_path / "t.csv")))
    assert {r["frame"] for r in table} == {"0", "1", "2"}
    check_biopython_reads(tmp_path / "c.pdb", table, [0, 1, 2])
    st = gemmi.read_structure(str(tmp_path / "c.pdb"))
    assert len(st) == 3
    for m, f in zip(st, range(3)):
        assert m.count_atom_sites() == sum(int(r["points"]) for r in table if int(r["frame"]) == f)
    # CONECT (after every model) joins the first model's points.
    pairs = conect_pairs(tmp_path / "c.pdb")
    assert len(pairs) == sum(int(r["points"]) - 1 for r in table if r["frame"] == "0")


def test_pymol_paths_are_relative_to_the_script(run):
    d, _, _, _ = run
    script = d / "sub" / "c.pml"
    loads = [l.split()[1].rstrip(",") for l in open(script) if l.startswith("load ")]
    assert len(loads) == 2
    assert not any(os.path.isabs(p) for p in loads)
    # From the script's folder they name the molecule and the centrelines.
    here = os.path.dirname(script)
    assert os.path.samefile(os.path.join(here, loads[0]), GRAMICIDIN)
    assert os.path.samefile(os.path.join(here, loads[1]), d / "sub" / "c.pdb")


def grid_of(frame):
    """(dims, voxel size, centre of voxel (0,0,0)) of the run's grid."""
    h = frame["voxel_A"]
    return (GRID,) * 3, h, np.array(frame["origin"]) + 0.5 * h


def alignment(mask_zyx, origin, h, frame):
    """Fraction of the channels' centreline points (the pore aside: it
    crosses constrictions narrower than the probe, outside the mask) that
    fall on mask voxels, for the map as read and for the map shifted one
    voxel along each axis: the map is placed right when the first wins."""
    pts = np.vstack([np.array(c["centreline"])[:, :3] for c in frame["channels"]
                     if c["kind"] == "channel"])
    ijk = np.rint((pts - origin) / h).astype(int)
    n = np.array(mask_zyx.shape[::-1])
    assert np.all((ijk >= 1) & (ijk < n - 1))

    def on(shift):
        q = ijk + shift
        return float(np.mean(mask_zyx[q[:, 2], q[:, 1], q[:, 0]] != 0))
    shifted = [on(np.array(s)) for s in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0),
                                          (0, 0, 1), (0, 0, -1))]
    return on(np.zeros(3, int)), max(shifted)


def test_mrc_mrcfile_validates_and_reads(run):
    import mrcfile
    d, _, stats, frame = run
    dims, h, origin = grid_of(frame)
    for name, mode in (("m.mrc", 0), ("o.mrc", 2)):
        assert mrcfile.validate(str(d / name), print_file=open(os.devnull, "w"))
        with mrcfile.open(str(d / name), permissive=False) as m:
            assert m.header.nversion == 20140 and int(m.header.mode) == mode
            assert m.data.shape == dims
            assert np.allclose([m.voxel_size.x, m.voxel_size.y, m.voxel_size.z], h, atol=1e-5)
            o = np.array([m.header.origin.x, m.header.origin.y, m.header.origin.z])
            assert np.allclose(o, origin, atol=1e-3)
            data = m.data.astype(np.float64)
            assert np.isclose(float(m.header.rms), data.std(), rtol=1e-5)
            assert np.isclose(float(m.header.dmean), data.mean(), rtol=1e-5)
            assert (m.header.dmin, m.header.dmax) == (data.min(), data.max())
            if name == "m.mrc":
                mask = m.data
                assert np.count_nonzero(mask) == int(stats["channel_voxels"]) > 100
                ours, shifted = alignment(mask, o, h, frame)
                assert ours >= 0.6 and ours > shifted + 0.2, (ours, shifted)
            else:
                occ = m.data
    # One frame: the occupancy is 1 on every channel voxel (and in the pore
    # spheres), 0 elsewhere.
    assert set(np.unique(occ)) == {0.0, 1.0}
    assert np.all(occ[mask != 0] == 1.0) and np.count_nonzero(occ) > np.count_nonzero(mask)


def test_mrc_gemmi_reads(run):
    import gemmi
    d, _, stats, frame = run
    dims, h, _ = grid_of(frame)
    m = gemmi.read_ccp4_map(str(d / "m.mrc"))
    assert (m.grid.nu, m.grid.nv, m.grid.nw) == dims
    assert np.isclose(m.grid.unit_cell.a / m.grid.nu, h, atol=1e-5)
    assert np.count_nonzero(np.array(m.grid, copy=False)) == int(stats["channel_voxels"])


def test_vtk_meshio_reads(run):
    import meshio
    d, _, stats, frame = run
    dims, h, origin = grid_of(frame)
    with open(d / "m.mrc", "rb") as f:
        f.seek(1024)
        mrc_mask = np.frombuffer(f.read(), dtype=np.int8)
    for name, field in (("m.vtk", "mask"), ("o.vtk", "occupancy")):
        mesh = meshio.read(str(d / name))
        assert mesh.points.shape == (np.prod(dims), 3)
        assert np.allclose(mesh.points[0], origin, atol=1e-5)
        assert np.allclose(mesh.points[-1], origin + (np.array(dims) - 1) * h, atol=1e-4)
        assert np.allclose(mesh.points[1] - mesh.points[0], [h, 0, 0], atol=1e-5)
        v = mesh.point_data[field].ravel()
        assert len(v) == np.prod(dims)
        if field == "mask":
            assert v.dtype == np.uint8
            # Point order (x fastest) and values are the MRC's.
            assert np.array_equal(v, mrc_mask.astype(np.uint8))
            assert np.count_nonzero(v) == int(stats["channel_voxels"])
        else:
            assert v.dtype.kind == "f" and set(np.unique(v)) == {0.0, 1.0}
            assert np.all(v[mrc_mask != 0] == 1.0)
