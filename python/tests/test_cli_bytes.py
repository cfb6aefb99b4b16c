"""The package computes what the command computes: the same vertex bytes
on the corpus, the same counters, from files and from arrays."""
import glob
import os

import numpy as np
import pytest
import vorball

from conftest import cli, corpus, parse_vertices, same_vertices

CASES = sorted(os.path.basename(p)[:-5] for p in glob.glob(corpus("inputs", "*.xyzr")))


def test_corpus_has_cases():
    assert len(CASES) >= 10


@pytest.mark.parametrize("case", CASES)
def test_corpus_case_same_bytes(case):
    path = corpus("inputs", case + ".xyzr")
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(path, device="ref")
    assert res.to_text() == out
    same_vertices(res, out)
    # The golden answer of the case, as its pipeline test reads it.
    gold = parse_vertices(open(corpus("golden", case + ".tsv")).read())
    assert len(res.ids) == len(gold[0])


@pytest.mark.parametrize("case", ["degree5_vertex", "contained_sphere", "large_offset"])
def test_arrays_of_a_file_same_bytes(case):
    """The doubles of a file's spheres, as float64 arrays: repr gives the
    file's decimals back, so the vertices are the command's."""
    path = corpus("inputs", case + ".xyzr")
    s = vorball.read(path)
    out, _ = cli("vertices", "--device", "ref", path)
    assert vorball.vertices(s.xyz, s.r, device="ref").to_text() == out


def test_crambin_pdb_same_bytes_and_formats():
    path = corpus("data", "1crn.pdb")
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(vorball.read(path), device="ref")
    assert res.to_text() == out
    assert len(res.t) == 1996 and res.certificate.complete
    assert res.certificate.certified == 1996
    assert res.certificate.text in out
    # The cells counter is the certificate line's; the quadruples (a count
    # of the proposer's work, which differs between a GPU's kernel forms and
    # the host's) are in the counters only, not in the output's bytes.
    c = res.certificate
    assert c.quadruples > 0 and c.cover_cells > 0
    assert "direction cover of %d cells, every root" % c.cover_cells in c.text
    assert "quadruples" not in c.text
    for fmt in ("json", "voronota"):
        o, _ = cli("vertices", "--device", "ref", "--output-format", fmt, path)
        assert res.to_text(fmt) == o


def test_crambin_float32_like_mdanalysis_same_bytes():
    """MDAnalysis keeps positions as float32: the shortest float32 decimals
    are the PDB's 3-decimal coordinates, so the command's bytes again."""
    path = corpus("data", "1crn.pdb")
    s = vorball.read(path)
    xyz32 = s.xyz.astype(np.float32)
    out, _ = cli("vertices", "--device", "ref", path)
    res = vorball.vertices(xyz32, s.r.astype(np.float32), device="ref")
    assert res.to_text() == out


VARYING = {"device_bytes_peak", "certify_parts", "cover_host_cells", "cover_handed_cells",
           "cover_resumed_patches",
           "cover_neighbours", "cover_max_cell_neighbours"}
# Arc closure's early tracing (arcs54): which vertices a part traced before
# the proposer returned depends on when the parts came, and so do the
# tracing predicates' counts (a part's searches run against its own map).
VARYING |= {"arc_filter_calls", "arc_filter_failures", "arc_exact_evals", "arc_candidates",
            "arc_early_parts", "arc_early_vertices", "arc_early_events"}
# Per tier of the device's arenas: how many launches and tasks each took,
# and the patches its tasks walked (the most in one task, and those of tasks
# that ran out), depend on which cells the host threads took first.
VARYING |= {"cover_%s_%s" % (w, t)
            for w in ("launches", "tasks", "patches", "task_max_patches", "wasted_patches",
                      "wasted_tasks")
            for t in ("first", "large", "handoff", "huge", "rerun")}
# What the first tier's arenas held (stop 54): of the cells the device took.
VARYING |= {"cover_first_records_max", "cover_first_labels_max", "cover_first_quadruples_max",
            "cover_first_past_half"}


def _printed(v):
    """A --stats line's value as the command prints it, parsed."""
    for conv in (int, float):
        try:
            return conv(v)
        except ValueError:
            pass
    return v


def _same_stats(err, stats):
    """Every line of the command's --stats is in the package's dict, with
    the same type and value: integers and texts equal, reals equal to the
    printed digits (%.3f, %.6f, %.6g, %.3g); seconds (keys ending in _s)
    and what a device's timing decides (its buffers' peak, the parts
    certified during the cover, the cells it handed to the host, its
    tiers' launches and tasks, the neighbour records built) vary run to run: only their type and sign count."""
    # The command's own process clock (process_*_s: reading, writing the
    # file, freeing) has no counterpart in a call that writes no file.
    want = dict(line.split("\t", 1) for line in err.splitlines()
                if "\t" in line and not line.startswith("process_"))
    assert list(want) == list(stats)
    for k, v in want.items():
        got, printed = stats[k], _printed(v)
        assert type(got) is type(printed) or isinstance(got, float), k
        if k.endswith("_s"):
            assert isinstance(got, float) and got >= 0.0, k
        elif k in VARYING:
            assert isinstance(got, int) and got >= 0, k
        elif isinstance(got, float):
            assert got == pytest.approx(printed, rel=5e-3, abs=5e-7), k
        else:
            assert got == printed, k


def test_stats_are_the_commands():
    path = corpus("inputs", "crambin_fragment.xyzr")
    _, err = cli("vertices", "--device", "ref", "--proposer", "sampling", "--stats", path)
    res = vorball.vertices(path, device="ref", proposer="sampling")
    _same_stats(err, res.stats)
    assert res.stats["certified_vertices"] == len(res.t)
    assert not res.certificate.complete and res.certificate.text == ""


def test_stats_every_field_of_the_cover(monkeypatch):
    """The cover's run on the OpenCL CPU device with arcs and the
    certification filter (VORBALL_DEVICE_CERT=1, for the command and the
    package alike): every field the command's --stats prints
    (device_bytes_peak, certify_*, judged_*, judge_s, arc_*), typed, from
    the library's table."""
    monkeypatch.setenv("VORBALL_DEVICE_CERT", "1")
    path = corpus("inputs", "crambin_fragment.xyzr")
    _, err = cli("vertices", "--device", "cpu", "--arcs", "--stats", path)
    res = vorball.vertices(path, device="cpu", arcs=True)
    _same_stats(err, res.stats)
    s = res.stats
    for k in ("device_bytes_peak", "certify_parts", "judged_vertex", "judged_not",
              "judged_open", "cover_quadruples", "arc_half_arcs", "arc_threads"):
        assert isinstance(s[k], int), k
    for k in ("certify_overlap_s", "certify_after_s", "judge_s", "arc_s", "arc_trace_s"):
        assert isinstance(s[k], float), k
    assert s["certified_vertices"] == len(res.t) == res.certificate.certified
    assert s["cover_quadruples"] == res.certificate.quadruples > 0
    assert s["arc_half_arcs"] == res.arcs.half_arcs > 0
    assert s["arc_closed"] + s["arc_infinite"] + s["arc_loops"] == s["arc_half_arcs"]
    # the filter judged two roots of every proposed quadruple, and the
    # vertices it proved are among the certified ones
    judged = s["judged_vertex"] + s["judged_not"] + s["judged_open"]
    assert judged == 2 * s["cover_quadruples"]
    assert 0 < s["judged_vertex"] <= s["certified_vertices"]
    if s["backend"] == "opencl":
        assert s["device_bytes_peak"] > 0  # the device held its buffers
    else:  # no OpenCL CPU device here: the reference ran (W760)
        assert s["device_bytes_peak"] == 0


def test_sampling_and_cover_same_vertices():
    path = corpus("inputs", "jittered_lattice.xyzr")
    a = vorball.vertices(path, device="ref")
    b = vorball.vertices(path, device="ref", proposer="sampling", samples=40)
    assert len(a.ids) == len(b.ids) > 0
    assert all(np.array_equal(x, y) for x, y in zip(a.ids, b.ids))
    assert np.array_equal(a.xyz, b.xyz) and np.array_equal(a.t, b.t)


def test_pocl_device_same_bytes():
    """The OpenCL CPU device (PoCL) gives the reference's bytes, as the
    command does (or falls back with W760 where there is none)."""
    path = corpus("inputs", "crambin_fragment.xyzr")
    ref = vorball.vertices(path, device="ref")
    cpu = vorball.vertices(path, device="cpu")
    assert cpu.to_text() == ref.to_text()
    assert cpu.backend == "opencl" or any(w.number == 760 for w in cpu.warnings)


def test_threads_do_not_change_bytes():
    path = corpus("inputs", "bcc_lattice.xyzr")
    texts = {vorball.vertices(path, device="ref", threads=t).to_text() for t in (1, 3)}
    assert len(texts) == 1
