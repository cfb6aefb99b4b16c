"""Every format the command reads, atom records, reading options, and the
frames of trajectories in an MDAnalysis-style loop."""
import struct

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, parse_vertices


def test_formats_of_crambin_agree():
    """The PDB, mmCIF and XYZR forms of crambin: the same atoms."""
    pdb = vorball.read(corpus("data", "1crn.pdb"))
    cif = vorball.read(corpus("data", "1crn.cif"))
    assert len(pdb) == len(cif) == 327
    assert np.array_equal(pdb.xyz, cif.xyz) and np.array_equal(pdb.r, cif.r)
    assert (pdb.decimals == cif.decimals).all()
    a = pdb.atoms
    assert a.dtype.names == ("serial", "name", "resname", "chain", "resseq", "icode", "altloc",
                             "element", "hetatm")
    assert (a["serial"][0], a["name"][0], a["resname"][0], a["chain"][0], a["resseq"][0],
            a["element"][0]) == (1, "N", "THR", "A", 1, "N")
    assert np.array_equal(a["resname"], cif.atoms["resname"])
    # The built-in radii of the element table.
    assert pdb.r[a["element"] == "C"][0] == 1.7 and pdb.r[a["element"] == "O"][0] == 1.52
    frag = vorball.read(corpus("inputs", "crambin_fragment.xyzr"))
    assert frag.atoms is None and np.array_equal(frag.xyz, pdb.xyz[:70])


def test_pqr_keeps_zero_radius_points():
    s = vorball.read(corpus("data", "1crn_apbs.pqr"))
    assert len(s) == 642 and (s.r == 0).sum() == 236
    assert any(w.number == 713 for w in s.warnings)
    dropped = vorball.read(corpus("data", "1crn_apbs.pqr"), zero_radius="drop")
    assert len(dropped) == 642 - 236


def test_options_as_the_command(tmp_path):
    radii = tmp_path / "radii.txt"
    radii.write_text("C 2.0\n")
    s = vorball.read(corpus("data", "1crn.pdb"), radii=radii, hydrogens=False)
    assert s.r[s.atoms["element"] == "C"][0] == 2.0
    out, _ = cli("vertices", "--device", "ref", "--radii", radii, corpus("data", "1crn.pdb"))
    assert vorball.vertices(s, device="ref").to_text() == out


def test_read_errors_carry_the_commands_number(tmp_path):
    bad = tmp_path / "bad.xyzr"
    bad.write_text("0 0 0 1\n1 1 1 x\n")
    with pytest.raises(vorball.VorballError) as e:
        vorball.read(bad)
    assert e.value.number == 101 and str(bad) + ":2:" in e.value.message
    _, err = cli("vertices", bad, rc=e.value.exit_status)
    assert "E101:" in err
    with pytest.raises(vorball.VorballError) as e:
        vorball.read(tmp_path / "missing.pdb")
    assert e.value.number == 8
    with pytest.raises(vorball.VorballError) as e:
        vorball.read(corpus("data", "1crn.pdb"), format="nonsense")
    assert e.value.number == 7
    with pytest.raises(vorball.VorballError) as e:
        vorball.read(corpus("data", "1crn.pdb"), model=2)
    assert e.value.number == 111


def test_mdanalysis_style_frame_loop():
    """for ts in trajectory: positions -> certified vertices, per frame."""
    path = corpus("data", "ngl_md_ascii_trj.pdb")
    models = []
    counts = []
    with vorball.Engine(device="ref") as eng:
        for ts in vorball.frames(path, stop=3):
            assert len(ts) == 183 and ts.exact
            models.append((ts.index, ts.model))
            res = eng.vertices(ts.xyz, ts.r)  # the positions, as MDAnalysis gives them
            counts.append(len(res.t))
            if ts.index == 2:  # one frame against the command
                out, _ = cli("vertices", "--device", "ref", "--model", ts.model, path)
                assert res.to_text() == out
    assert models == [(0, 1), (1, 2), (2, 3)]
    assert all(c > 500 for c in counts)
    n = sum(1 for _ in vorball.frames(path))
    assert n == 51
    picked = [(f.index, f.model) for f in vorball.frames(path, start=10, stop=20, step=4)]
    assert picked == [(10, 11), (14, 15), (18, 19)]


def write_dcd(path, frames):
    """A CHARMM DCD (little endian) of float32 frames, each (natoms, 3)."""
    def record(b):
        return struct.pack("<i", len(b)) + b + struct.pack("<i", len(b))
    ic = [0] * 20
    ic[0], ic[1], ic[2], ic[19] = len(frames), 1, 1, 24
    head = b"CORD" + struct.pack("<9i", *ic[:9]) + struct.pack("<f", 0.002) + \
        struct.pack("<10i", *ic[10:])
    out = record(head) + record(struct.pack("<i", 1) + b"vorball test".ljust(80)) + \
        record(struct.pack("<i", frames[0].shape[0]))
    for f in frames:
        for axis in range(3):
            out += record(np.ascontiguousarray(f[:, axis], dtype="<f4").tobytes())
    path.write_bytes(out)


def test_dcd_frames(tmp_path):
    """A DCD over its topology: frames of doubles only (float32 values);
    vertices certify the float64 repr decimals of those doubles, which is
    what the command computes for a file holding them."""
    top = vorball.read(corpus("inputs", "crambin_fragment.xyzr"))
    rng = np.random.default_rng(3)
    frames = [top.xyz + rng.normal(0, 0.05, top.xyz.shape) for _ in range(3)]
    write_dcd(tmp_path / "t.dcd", frames)
    got = list(vorball.frames(corpus("inputs", "crambin_fragment.xyzr"),
                              trajectory=tmp_path / "t.dcd"))
    assert [(f.index, f.model) for f in got] == [(0, 1), (1, 2), (2, 3)]
    f = got[1]
    assert not f.exact and f.decimals is None
    assert np.array_equal(f.xyz, frames[1].astype(np.float32).astype(np.float64))
    res = vorball.vertices(f, device="ref")
    text = tmp_path / "frame.xyzr"
    text.write_text("".join("%r %r %r %r\n" % (x, y, z, r)
                            for (x, y, z), r in zip(f.xyz.tolist(), f.r.tolist())))
    out, _ = cli("vertices", "--device", "ref", text)
    assert res.to_text() == out
    assert len(parse_vertices(out)[0]) > 100
    # Channels take the frame's doubles as they are, as the command does.
    with vorball.Engine(device="ref") as eng:
        ch = [eng.channels(g, grid=32) for g in got]
    assert [(c.frame, c.model) for c in ch] == [(0, 1), (1, 2), (2, 3)]
    assert all(len(c) for c in ch)  # channels found: the comparison below has rows
    assert ch[1].spheres is got[1]
    out, _ = cli("channels", "--device", "ref", "--grid", 32, "--dcd", tmp_path / "t.dcd",
                 corpus("inputs", "crambin_fragment.xyzr"))
    assert "".join(c.csv.split("\n", 1)[1] for c in ch) == out.split("\n", 1)[1]


def test_frames_errors(tmp_path):
    write_dcd(tmp_path / "t.dcd", [np.zeros((5, 3))])
    with pytest.raises(vorball.VorballError) as e:
        list(vorball.frames(corpus("inputs", "crambin_fragment.xyzr"), trajectory=tmp_path / "t.dcd"))
    assert e.value.number == 116  # atom counts differ (E116: trajectory and topology disagree)
    with pytest.raises(vorball.VorballError) as e:
        vorball.frames(corpus("data", "1crn.pdb"), step=0)
    assert e.value.number == 7


def test_frames_detect_past_a_long_header(tmp_path):
    """frames() detects the format as read() does, past any header (issue 28:
    a PQR behind 140 KiB of REMARK lines was read as PDB, element radii)."""
    atoms = [l for l in open(corpus("data", "1crn_apbs.pqr")) if l.startswith("ATOM")]
    p = tmp_path / "long.pqr"
    p.write_text("REMARK   1 a long PDB2PQR header line, padded to seventy characters..\n" * 2000
                 + "".join(atoms))
    whole = vorball.read(p)
    frame = next(iter(vorball.frames(p)))
    assert len(whole) == len(frame) == 642
    assert np.array_equal(whole.r, frame.r) and np.array_equal(whole.xyz, frame.xyz)
    assert frame.r[0] == 2.0  # the file's radius, not nitrogen's 1.55


def test_gro_count_must_match_the_atom_lines(tmp_path):
    """A GRO whose count says 3 of its 6 atom lines: E101 at the fourth atom
    line (issue 28: read() took 3 atoms, silently)."""
    atoms = "".join("    1ALA     CA    %d   %5.3f   0.100   0.100\n" % (k, 0.1 + 0.3 * k)
                    for k in range(6))
    p = tmp_path / "short.gro"
    p.write_text("t\n3\n" + atoms + "   1.0 1.0 1.0\n")
    with pytest.raises(vorball.VorballError) as e:
        vorball.read(p)
    assert e.value.number == 101 and str(p) + ":6:" in e.value.message
    p.write_text("t\n6\n" + atoms + "   1.0 1.0 1.0\n")
    assert len(vorball.read(p)) == 6


def two_copy_assembly(tmp_path):
    """1crn.cif with assembly 1 built by two operators: the identity and a
    move by 40 Angstrom along x."""
    text = open(corpus("data", "1crn.cif")).read()
    head, rest = text.split("_pdbx_struct_assembly_gen.assembly_id", 1)
    tail = rest.split("# \n", 2)[2]
    ops = ("loop_\n_pdbx_struct_oper_list.id\n_pdbx_struct_oper_list.type\n" +
           "".join("_pdbx_struct_oper_list.%s\n" % k for k in (
               "matrix[1][1]", "matrix[1][2]", "matrix[1][3]", "vector[1]",
               "matrix[2][1]", "matrix[2][2]", "matrix[2][3]", "vector[2]",
               "matrix[3][1]", "matrix[3][2]", "matrix[3][3]", "vector[3]")) +
           "1 'identity operation' 1 0 0 0 0 1 0 0 0 0 1 0\n"
           "2 'translation' 1 0 0 40.0 0 1 0 0 0 0 1 0\n# \n")
    path = tmp_path / "two.cif"
    path.write_text(head + "_pdbx_struct_assembly_gen.assembly_id 1\n"
                    "_pdbx_struct_assembly_gen.oper_expression '1,2'\n"
                    "_pdbx_struct_assembly_gen.asym_id_list A\n# \n" + ops + tail)
    return path


def test_assembly_as_the_command(tmp_path):
    path = two_copy_assembly(tmp_path)
    one = vorball.read(path)
    two = vorball.read(path, assembly=1)
    assert len(two) == 2 * len(one)
    assert np.array_equal(two.xyz[:len(one)], one.xyz)
    assert np.array_equal(two.decimals[len(one):, 0] - two.decimals[:len(one), 0],
                          np.full(len(one), 40))
    # The command's sphere table (--atoms) of --assembly 1: the same exact numbers.
    atoms = tmp_path / "atoms.tsv"
    cli("jfa", "--protein", path, "--assembly", "1", "--atoms", atoms, "-n", "2", "-V", "jfa",
        "--device", "ref")
    rows = [line.split("\t") for line in atoms.read_text().splitlines()
            if line and not line.startswith(("#", "id\t"))]
    assert len(rows) == len(two)
    xyz = np.array([[float(v) for v in r[-4:-1]] for r in rows])
    assert np.array_equal(xyz, two.xyz)
    # Frames take it too; the ranges are the library's, with the command's words.
    assert len(next(iter(vorball.frames(path, assembly=1)))) == len(two)
    _, err = cli("jfa", "--protein", path, "--assembly", "0", rc=2)
    for bad in (0, 10 ** 7, 10 ** 30):
        with pytest.raises(vorball.VorballError) as e:
            vorball.read(path, assembly=bad)
        assert e.value.number == 7 and e.value.message in err
