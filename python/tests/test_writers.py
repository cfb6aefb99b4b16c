"""The command's other writers from Python, each the library's: the
vertices results page (`vertices --html`), the sphere table (`--atoms`)
and the cells JSON (`cells --json`), compared with the command's bytes."""
import json

import pytest
import vorball

from conftest import cli, corpus

# The provenance members the command's JSON carries first (issue 35).
PROVENANCE = ("tool", "input", "spheres", "options")


def test_vertices_page_as_the_command(tmp_path):
    path = corpus("inputs", "bcc_lattice.xyzr")
    page = tmp_path / "cmd.html"
    cli("vertices", path, "--device", "ref", "--html", page)
    r = vorball.vertices(path, device="ref")
    mine = tmp_path / "py.html"
    r.write_html(mine)
    assert mine.read_bytes() == page.read_bytes()
    assert b"vorball vertices " + str(path).encode() in page.read_bytes()


def test_vertices_page_size_refused(tmp_path):
    import numpy as np
    g = np.arange(13) * 4.0
    xyz = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)[:2001]
    rng = np.random.default_rng(3)
    xyz = xyz + rng.uniform(-0.3, 0.3, xyz.shape)
    r = vorball.vertices(xyz, np.full(len(xyz), 1.2), device="ref")
    with pytest.raises(vorball.VorballError) as e:
        r.write_html(tmp_path / "big.html")
    assert e.value.number == 133
    assert not (tmp_path / "big.html").exists()


def test_atoms_table_as_the_command(tmp_path):
    pdb = corpus("data", "1crn.pdb")
    atoms = tmp_path / "atoms.tsv"
    cli("reference", corpus("inputs", "bcc_lattice.xyzr"), "--atoms", atoms)
    assert vorball.read(corpus("inputs", "bcc_lattice.xyzr")).atoms_text() == atoms.read_text()
    cli("jfa", "--protein", pdb, "--atoms", atoms, "-n", "2", "-V", "jfa", "--device", "ref")
    text = vorball.read(pdb).atoms_text()
    assert text == atoms.read_text()
    assert len([line for line in text.splitlines() if not line.startswith("#")]) >= 327


def test_cells_json_as_the_command(tmp_path):
    pdb = corpus("data", "1crn.pdb")
    out, _ = cli("cells", pdb, "--json", "--tolerance", "1e-2", "--max-patches", "300",
                 provenance=True)
    c = vorball.cells(pdb, tolerance=1e-2, max_patches=300)
    doc = json.loads(out)
    for k in PROVENANCE:
        doc.pop(k)
    assert c.to_json() == doc
    assert len(doc["atoms"]) == len(c) and doc["residues"] and doc["chains"]
    # The same digits as the command's bytes, the provenance members aside.
    head = out.index('"atoms"')
    assert c.json[c.json.index('"atoms"'):] == out[head:]
