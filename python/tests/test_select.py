"""select= (issue 32): the grammar of `--select` on vertices, cells and
channels through the package, the same atoms and numbers as the command,
and E118 for a bad or empty selection."""
import pytest
import vorball

from conftest import cli, corpus, same_vertices

TOXIN = corpus("data", "1chb_hole2.pdb")
GRAMICIDIN = corpus("data", "1grm_single_hole2.pdb")
PART = "chain D and resid 1:10"


def test_spheres_select_keeps_order_and_decimals():
    s = vorball.read(TOXIN)
    t = s.select(PART)
    keep = (s.atoms["chain"] == "D") & (s.atoms["resseq"] >= 1) & (s.atoms["resseq"] <= 10)
    assert t.n == int(keep.sum()) > 50
    assert (t.xyz == s.xyz[keep]).all() and (t.r == s.r[keep]).all()
    assert (t.line == s.line[keep]).all()
    assert t.decimals is not None


def test_vertices_and_cells_select_as_the_command():
    r = vorball.vertices(TOXIN, device="ref", select=PART)
    out, _ = cli("vertices", "--device", "ref", "--select", PART, TOXIN)
    same_vertices(r, out)
    c = vorball.cells(TOXIN, select=PART)
    assert len(c.volume) == vorball.read(TOXIN).select(PART).n


def test_channels_select_as_the_command():
    ch = vorball.channels(GRAMICIDIN, device="ref", grid=64, select="chain A")
    out, _ = cli("channels", "--device", "ref", "--grid", 64, "--select", "chain A", GRAMICIDIN)
    assert ch.csv == out


@pytest.mark.parametrize("expr,where", [("chain D and", "character 12"),
                                        ("resid 5:2", "character 7"),
                                        ("chain Q", "selects none")])
def test_bad_selection_is_e118(expr, where):
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(TOXIN, select=expr)
    assert e.value.number == 118 and where in str(e.value)
