"""Channels through the package: the command's table and JSON, the tables
as NumPy structured arrays at full precision, pore profiles, and a loop
over the frames of a trajectory on one device."""
import csv
import io
import json

import numpy as np
import pytest
import vorball

from conftest import cli, corpus

GRAMICIDIN = corpus("data", "1grm_single_hole2.pdb")
TRAJ = corpus("data", "ngl_md_ascii_trj.pdb")


@pytest.fixture(scope="module")
def gramicidin():
    return vorball.channels(vorball.read(GRAMICIDIN), grid=64, device="ref")


def test_stage_clocks(gramicidin):
    """The call's per-stage milliseconds (issue 33): the keys of the
    command's JSON "ms" but "read" (the call reads nothing), none negative,
    the pore's steps within the pore stage."""
    ms = gramicidin.ms
    assert list(ms) == ["prepare", "upload", "jfa", "masks", "analysis", "cells", "refine",
                        "sweep", "verdict", "lining", "pore", "total"]
    assert all(v >= 0.0 for v in ms.values())
    steps = ms["cells"] + ms["refine"] + ms["sweep"] + ms["verdict"] + ms["lining"]
    assert steps <= ms["pore"] + 1e-3 and ms["pore"] <= ms["total"] + 1e-3


def test_same_table_as_the_command(gramicidin):
    """The same call gives the same answer: the pore sweep included."""
    out, _ = cli("channels", "--device", "ref", "--grid", 64, GRAMICIDIN)
    assert gramicidin.csv == out
    j, _ = cli("channels", "--device", "ref", "--grid", 64, "--json", GRAMICIDIN)
    mine, theirs = gramicidin.to_json(), json.loads(j)
    # The command's provenance (issue 35): its tool and command line.
    assert theirs.pop("tool").startswith("vorball ")
    assert theirs.pop("options") == "channels --grid 64 --json " + GRAMICIDIN
    assert theirs.pop("clock")["frames"] == 1  # the run's clock (the command's run over frames)
    for frame in (mine["frames"][0], theirs["frames"][0]):
        frame.pop("ms")  # timings
        frame.pop("clock")
    assert mine == theirs
    s = vorball.read(GRAMICIDIN)
    no_pore = vorball.channels(s, grid=64, device="ref", no_pore=True, cavities=True)
    out, _ = cli("channels", "--device", "ref", "--grid", 64, "--no-pore", "--cavities", GRAMICIDIN)
    assert no_pore.csv == out and "pore" not in no_pore.table["kind"]


def test_profile_and_pore_as_the_command(gramicidin, tmp_path):
    """The frame's --profile rows and pore (axis, openings, conductance)
    through the library's handle: the command's profile file byte for
    byte, the pore's figures those of the command's JSON."""
    prof = tmp_path / "p.csv"
    cli("channels", "--device", "ref", "--grid", 64, "--profile", prof, GRAMICIDIN)
    assert gramicidin.profile_csv == prof.read_text()
    assert gramicidin.profile_csv.count("\n") == 1 + sum(len(c) for c in gramicidin.centrelines)
    p = gramicidin.pore
    assert p is not None and p["open_lo"] and p["open_hi"]
    assert abs(sum(x * x for x in p["axis"]) - 1.0) < 1e-12
    row = gramicidin.table[0]
    assert row["kind"] == "pore"
    assert "%.1f" % p["g_macro_pS"] == row["g_macro_pS"]  # the column as written (%.1f)
    none = vorball.channels(vorball.read(GRAMICIDIN), grid=64, device="ref", no_pore=True)
    assert none.pore is None


def test_pore_at_the_defaults_as_the_command():
    """Gramicidin at every default (grid 128, probe 1.4, the pore sweep):
    1.337 A in the table of `vorball channels` and of vorball.channels
    (1.84 A before the binding had the sweep)."""
    out, _ = cli("channels", "--device", "ref", GRAMICIDIN)
    ch = vorball.channels(vorball.read(GRAMICIDIN), device="ref")
    assert ch.csv == out
    assert ch.table["kind"][0] == "pore" and "%.3f" % ch.table["bottleneck_A"][0] == "1.337"
    assert "%.3f" % ch.profile(0)[1].min() == "1.337"


def test_pore_options_as_the_command():
    """Options of the pore by the command's names: axis, through, sample,
    end_radius, ignore; their ranges are the library's."""
    s = vorball.read(GRAMICIDIN)
    ch = vorball.channels(s, grid=64, device="ref", axis=(0, 0, 2), through=[0, 0, 1],
                          sample=0.5, end_radius=5, ignore="FOR,ETA")
    out, _ = cli("channels", "--device", "ref", "--grid", 64, "--axis", "0,0,2", "--through",
                 "0,0,1", "--sample", 0.5, "--end-radius", 5, "--ignore", "FOR,ETA", GRAMICIDIN)
    assert ch.csv == out
    for kw in ({"sample": 9.0}, {"axis": (0, 0, 0)}, {"axis": (1, 2)}, {"no_pore": True,
               "through": (0, 0, 0)}, {"grid": True}, {"probe": "1.4"}, {"bogus": 1}):
        with pytest.raises(vorball.VorballError) as e:
            vorball.channels(s, **{"device": "ref", "grid": 32, **kw})
        assert e.value.number == 7, kw
    table = vorball.channel_options()
    assert table["probe"][:4] == ("real", 0.0, 20.0, "1.4")
    assert table["grid"][:4] == ("pow2", 16.0, 1024.0, "128")
    assert "probe" in vorball.channels.__doc__ and "min_length" in vorball.channels.__doc__


def test_table_is_the_csv_at_full_precision(gramicidin):
    t = gramicidin.table
    rows = list(csv.DictReader(io.StringIO(gramicidin.csv)))
    assert len(t) == len(rows) >= 2
    assert list(t.dtype.names) == list(rows[0].keys())  # every column the library writes
    for k, row in enumerate(rows):
        for name in t.dtype.names:
            v = t[name][k]
            if t.dtype[name].kind == "f":
                assert "%.3f" % v == row[name], name
            elif t.dtype[name].kind == "b":
                assert int(v) == int(row[name]), name
            else:
                assert str(v) == row[name], name
    assert t["kind"][0] == "pore" and t["kind"][1] == "channel"


def test_profiles_and_lining(gramicidin):
    s = gramicidin.spheres
    for k, row in enumerate(gramicidin.table):
        c = gramicidin.centrelines[k]
        dist, r = gramicidin.profile(k)
        assert len(c) == row["points"] and len(r) == len(c)
        assert np.all(np.diff(dist) > 0) and dist[0] == 0
        assert abs(dist[-1] - row["length_A"]) < 1e-6 * max(1, row["length_A"])
        assert r.min() == row["bottleneck_A"]
        # The clearance is the distance to the bounding atom's surface.
        a = c["atom"]
        clear = np.linalg.norm(np.column_stack([c["x"], c["y"], c["z"]]) - s.xyz[a], axis=1) - s.r[a]
        assert np.allclose(clear, r, atol=1e-9)
        lining = gramicidin.lining[k]
        assert len(lining) == row["lining_atoms"] and np.all(np.diff(lining) > 0)
        residues = sorted({"%s:%s%d" % (s.atoms["chain"][i], s.atoms["resname"][i],
                                        s.atoms["resseq"][i]) for i in lining})
        assert residues == sorted(row["lining_residues"].split(";"))


def test_trajectory_loop_on_one_engine():
    """Frames 0..2 on one opened device: the command's rows over the same
    frames (the later frames sweep the first frame's pore axis)."""
    out, _ = cli("channels", "--device", "ref", "--grid", 64, "--frames", "0:3", TRAJ)
    rows = []
    with vorball.Engine(device="ref") as eng:
        for f in vorball.frames(TRAJ, stop=3):
            ch = eng.channels(f, grid=64)
            assert (ch.frame, ch.model) == (f.index, f.model)
            rows.extend(ch.csv.splitlines()[1:])
    assert "\n".join([out.splitlines()[0]] + rows) + "\n" == out


def test_arrays_and_flags():
    s = vorball.read(GRAMICIDIN)
    ch = vorball.channels(s.xyz, s.r, grid=32, device="ref", flags=True)
    bits = vorball.channel_flags()
    assert ch.flags.shape == (32, 32, 32)
    assert np.count_nonzero(ch.flags & bits["channel"]) == ch.channel_voxels
    # No atom records from arrays: lining residues are atom indices.
    assert all(r.startswith("#") for row in ch.table for r in row["lining_residues"].split(";"))


def test_channel_errors():
    s = vorball.read(GRAMICIDIN)
    for kw in ({"grid": 100}, {"probe": -1.0}, {"jfa": "nope"}, {"device": "tpu"}):
        with pytest.raises(vorball.VorballError) as e:
            vorball.channels(s, **{"device": "ref", **kw})
        assert e.value.number == 7, kw


def test_example_script(tmp_path):
    """papers/'s example: per-frame vertices and pore profiles of a trajectory."""
    import subprocess
    import sys
    script = corpus("..", "papers", "facet-jfa-and-channels", "trajectory_python.py")
    p = subprocess.run([sys.executable, script, "--frames", "3", "--device", "ref", "--out",
                        str(tmp_path), "--no-plot"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    rows = [l.split("\t") for l in (tmp_path / "frames.tsv").read_text().splitlines()[1:]]
    assert [int(r[0]) for r in rows] == [0, 1, 2]
    assert all(int(r[2]) > 1000 and r[3] == "1" for r in rows)  # vertices, complete
    first = vorball.channels(next(iter(vorball.frames(TRAJ))), grid=64, device="ref")
    assert float(rows[0][5]) == round(first.table["bottleneck_A"][0], 4)


TOXIN = corpus("data", "1chb_hole2.pdb")


def _turned_toxin(path):
    """1chb as two models, the second turned 16 degrees about x and moved
    1.5 A along x (tests/pipeline/axis_select.sh's file)."""
    import math
    atoms = [line for line in open(TOXIN) if line.startswith(("ATOM", "HETATM"))]
    with open(path, "w") as f:
        for m, deg in enumerate((0, 16)):
            c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
            f.write("MODEL     %4d\n" % (m + 1))
            for line in atoms:
                x, y, z = float(line[30:38]), float(line[38:46]), float(line[46:54])
                f.write(line[:30] + "%8.3f%8.3f%8.3f" % (x + 1.5 * m, c * y - s * z, s * y + c * z)
                        + line[54:])
            f.write("ENDMDL\n")
        f.write("END\n")


@pytest.mark.parametrize("refit", [True, False])
def test_frames_with_axis_refit_as_the_command(tmp_path, refit):
    """Issue 32: the frames of a trajectory through one Engine with
    axis_refit=True give the rows of `vorball channels --axis-refit` (the
    second frame's axis refitted on its own atoms: turned 16 degrees with
    the molecule), and without it the rows of the fixed axis; the two
    differ, so the keyword is not ignored."""
    path = str(tmp_path / "chb2.pdb")
    _turned_toxin(path)
    args = ["--axis-refit"] if refit else []
    out, _ = cli("channels", "--device", "ref", "--grid", 64, "--json", *args, path)
    theirs = json.loads(out)["frames"]
    rows, mine = [], []
    with vorball.Engine(device="ref") as eng:
        for f in vorball.frames(path):
            ch = eng.channels(f, grid=64, axis_refit=refit)
            mine.extend(ch.to_json()["frames"])
            rows.extend(ch.csv.splitlines()[1:])
    csv_out, _ = cli("channels", "--device", "ref", "--grid", 64, *args, path)
    assert "\n".join([csv_out.splitlines()[0]] + rows) + "\n" == csv_out
    for a, b in zip(mine, theirs):
        assert a["pore"]["axis"] == b["pore"]["axis"]
    assert len(mine) == len(theirs) == 2
    turned = theirs[1]["pore"]["axis"] != theirs[0]["pore"]["axis"]
    assert turned == refit


def test_frames_as_the_command(tmp_path):
    """Every frame through the library's run over frames
    (vorball.channels_frames): the command's table, statistics (less their
    clocks), centrelines, profile, per-frame volumes, occupancy and JSON
    (less its provenance and clocks) on the XTC, frames 1:9:2."""
    xtc = corpus("data", "ngl_md_10frames.xtc")
    sel = ["--grid", 64, "--device", "ref", "--traj", xtc, "--frames", "1:9:2"]
    cli("channels", *sel, "-o", tmp_path / "c.csv", "--stats-file", tmp_path / "c.stats",
        "--centerlines", tmp_path / "c.pdb", "--profile", tmp_path / "c.prof",
        "--volume", tmp_path / "c%d.mrc", "--fixed-grid", "--occupancy", tmp_path / "c.occ.mrc",
        TRAJ)
    r = vorball.channels_frames(TRAJ, xtc, grid=64, device="ref", start=1, stop=9, step=2,
                                stats=True, centerlines=tmp_path / "p.pdb", profile=True,
                                volume=tmp_path / "p%d.mrc", fixed_grid=True,
                                occupancy=tmp_path / "p.occ.mrc")
    assert r.selected == r.analysed == 4
    assert set(r.series["frame"]) <= {1, 3, 5, 7}  # the frames with a pore
    assert r.text == (tmp_path / "c.csv").read_text()
    untimed = lambda text: [",".join(row.split(",")[:12]) for row in text.splitlines()]
    assert untimed(r.stats_csv) == untimed((tmp_path / "c.stats").read_text())
    assert r.centrelines_pdb == (tmp_path / "c.pdb").read_text() == (tmp_path / "p.pdb").read_text()
    assert r.profile_csv == (tmp_path / "c.prof").read_text()
    for name in ["%d.mrc" % k for k in (1, 3, 5, 7)] + [".occ.mrc"]:
        assert (tmp_path / ("p" + name)).read_bytes() == (tmp_path / ("c" + name)).read_bytes()
    j, _ = cli("channels", *sel, "--json", TRAJ)
    mine, theirs = json.loads(vorball.channels_frames(
        TRAJ, xtc, grid=64, device="ref", start=1, stop=9, step=2, json=True).text), json.loads(j)
    theirs.pop("tool"), theirs.pop("options")
    for doc in (mine, theirs):
        assert doc.pop("clock")["frames"] == 4  # the run's clock: frames 1, 3, 5, 7
        for frame in doc["frames"]:
            frame.pop("ms"), frame.pop("clock")
    assert mine == theirs
    with pytest.raises(vorball.VorballError, match="--fixed-grid"):
        vorball.channels_frames(TRAJ, xtc, grid=64, device="ref", occupancy=tmp_path / "x.mrc")
    assert not (tmp_path / "x.mrc").exists()
    # One structure: its pore in the series, the stage picture of --png.
    cli("channels", "--grid", 64, "--device", "ref", "--png", tmp_path / "g.png", "-o",
        tmp_path / "g.csv", GRAMICIDIN)
    g = vorball.channels_frames(GRAMICIDIN, grid=64, device="ref", png=True)
    assert g.text == (tmp_path / "g.csv").read_text()
    bottleneck = float(g.text.splitlines()[1].split(",")[6])
    assert len(g.series) == 1 and "%.3f" % g.series["rmin"][0] == "%.3f" % bottleneck
    ihdr = (tmp_path / "g.png").read_bytes()[16:24]
    w, h = int.from_bytes(ihdr[:4], "big"), int.from_bytes(ihdr[4:], "big")
    assert g.stages.shape == (h, w, 3) and g.stages.any()
