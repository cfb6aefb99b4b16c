"""progress= (issue 35): the library's progress callback reaches a Python
callable with (stage, done, total), done never decreasing within a run of a
stage and ending at total; the results are the same with and without it; a
callable that raises is reported as unraisable and does not stop the run."""
import sys

import numpy as np
import pytest

import vorball
from conftest import corpus

CRAMBIN = corpus("data", "1crn.pdb")


def runs_of(calls):
    """Per stage, the runs of done counts (a new run starts at done 0)."""
    runs = {}
    for stage, done, total in calls:
        r = runs.setdefault(stage, [])
        if not r or done == 0:
            r.append([])
        r[-1].append((done, total))
    return runs


def check_monotone_to_total(calls, stages):
    runs = runs_of(calls)
    for s in stages:
        assert s in runs, "no %s progress in %s" % (s, sorted(runs))
        for run in runs[s]:
            dones = [d for d, _ in run]
            assert dones == sorted(dones), "%s: done decreases: %s" % (s, dones)
            assert all(t == run[-1][1] for _, t in run), "%s: total changes" % s
            assert run[-1][0] == run[-1][1] > 0, "%s ends at %s" % (s, run[-1])


def test_vertices_progress_monotone_and_complete():
    calls = []
    res = vorball.vertices(CRAMBIN, device="ref", threads=2,
                           progress=lambda s, d, t: calls.append((s, d, t)))
    for s, d, t in calls:
        assert isinstance(s, str) and isinstance(d, int) and isinstance(t, int)
    check_monotone_to_total(calls, ["cover", "certify"])
    # bounded: about one call per 1/1000 of each run, not one per cell
    assert len(calls) <= 2 * 1002 + 10
    plain = vorball.vertices(CRAMBIN, device="ref", threads=2)
    assert res.to_text("tsv") == plain.to_text("tsv")


def test_verify_arcs_progress():
    res = vorball.vertices(CRAMBIN, device="ref")
    calls = []
    rep = vorball.verify(CRAMBIN, res, arcs=True,
                         progress=lambda s, d, t: calls.append((s, d, t)))
    check_monotone_to_total(calls, ["arcs"])
    assert rep.ok


@pytest.mark.filterwarnings("ignore::vorball.VorballWarning")
def test_channels_progress_frame():
    calls = []
    vorball.channels(CRAMBIN, device="ref", progress=lambda *a: calls.append(a))
    assert calls == [("frames", 1, 1)]


def test_progress_exception_does_not_stop_the_run(monkeypatch):
    seen = []
    monkeypatch.setattr(sys, "unraisablehook", lambda u: seen.append(u.exc_type))
    calls = []

    def bad(stage, done, total):
        calls.append(done)
        raise ValueError("stop drawing")

    res = vorball.vertices(CRAMBIN, device="ref", progress=bad)
    assert len(calls) == 1          # no call after the one that raised
    assert seen == [ValueError]
    plain = vorball.vertices(CRAMBIN, device="ref")
    assert res.to_text("tsv") == plain.to_text("tsv")
    assert np.array_equal(res.xyz, plain.xyz)


def test_progress_must_be_callable():
    with pytest.raises(TypeError):
        vorball.vertices(CRAMBIN, device="ref", progress=3)
