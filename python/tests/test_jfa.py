"""vorball.jfa as `vorball jfa`: the same seeds, runs, counts and checks
(the JSON document equal but its times), the picture equal to the
command's --png pixels, seeds from a file, from arrays and from a
protein, and the refused options with the command's words (the ranges of
vbj_setup_check)."""
import json
import struct
import zlib

import numpy as np
import pytest
import vorball

from conftest import cli, corpus

# The figures that are times (they differ between any two runs).
TIMES = {"time_ms", "time_ms_min", "gpu_ms", "fill_ms", "prep_transfer_ms", "prep_ms", "exact_ms"}


def untimed(doc):
    doc = {k: v for k, v in doc.items() if k not in TIMES}
    doc["runs"] = [{k: v for k, v in r.items() if k not in TIMES} for r in doc["runs"]]
    return doc


def png_pixels(path):
    """The RGB pixels of an 8-bit RGB PNG (no interlace), unfiltered."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert (depth, colour) == (8, 2)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = 3 * w
    out = np.zeros((h, stride), dtype=np.int32)
    prev = np.zeros(stride, dtype=np.int32)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = np.frombuffer(raw, dtype=np.uint8, count=stride, offset=y * (stride + 1) + 1)
        cur = line.astype(np.int32)
        if f == 2:
            cur = (cur + prev) & 255
        elif f in (1, 3, 4):
            cur = cur.copy()
            for x in range(stride):
                a = cur[x - 3] if x >= 3 else 0
                b = prev[x]
                c = prev[x - 3] if x >= 3 else 0
                if f == 1:
                    pred = a
                elif f == 3:
                    pred = (a + b) // 2
                else:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
                cur[x] = (cur[x] + pred) & 255
        out[y] = cur
        prev = cur
    return out.astype(np.uint8).reshape(h, w, 3)


def test_jfa_as_the_command():
    out, _ = cli("jfa", "-n", "64", "-k", "40", "--device", "ref", "-V", "all", "--check",
                 "--json")
    j = vorball.jfa(size=64, k=40, device="ref", variant="all", check=True)
    assert untimed(j.to_json()) == untimed(json.loads(out))
    assert [r.variant for r in j.runs] == ["jfa", "jfa+1", "jfa+2", "1+jfa", "facet", "exact"]
    assert j.source == "uniform, rng 1" and j.seeds == 40 and j.n == 64
    exact = j.runs[-1]
    assert exact.labels.shape == (64, 64) and exact.metrics["wrong"] == 0
    assert exact.metrics["differ"] == 0
    # Every variant's counts are the document's, and labels lie among the seeds.
    for r, d in zip(j.runs, json.loads(out)["runs"]):
        assert r.counts["pixels_processed"] == d["pixels_processed"]
        assert r.metrics["wrong"] == d["wrong"]
        assert int(r.labels.max()) < 40
    # The table's lines but the times.
    text, _ = cli("jfa", "-n", "64", "-k", "40", "--device", "ref", "-V", "all", "--check")
    strip = lambda t: [line.split()[:1] + line.split()[3:] for line in t.splitlines()]  # noqa
    assert strip(j.text) == strip(text)


def test_jfa_picture_is_the_png(tmp_path):
    png = tmp_path / "j.png"
    cli("jfa", "-d", "3", "-n", "32", "-k", "30", "--dist", "clustered", "--rng", "5",
        "--device", "ref", "-V", "exact", "--png", png, "--slice", "3,16,31")
    j = vorball.jfa(dim=3, size=32, k=30, dist="clustered", rng=5, device="ref",
                    variant="exact")
    pic = j.picture([3, 16, 31])
    assert pic.shape == (32, 96, 3)
    assert np.array_equal(pic, png_pixels(png))
    assert (pic == 0).all(axis=2).any()  # boundaries are black
    with pytest.raises(vorball.VorballError) as e:
        j.picture([32])
    assert e.value.number == 7 and "bad --slice" in str(e.value)


def test_jfa_seed_file_and_arrays(tmp_path):
    seeds = np.array([[3.25, 4.0], [20.5, 7.75], [11.0, 25.5], [28.0, 28.0], [0.0, 31.0]])
    path = tmp_path / "seeds.txt"
    path.write_text("".join("%r %r\n" % (float(x), float(y)) for x, y in seeds))
    out, _ = cli("jfa", path, "-n", "32", "--device", "ref", "-V", "jfa,exact", "--check",
                 "--json")
    f = vorball.jfa(path, size=32, device="ref", variant="jfa,exact", check=True)
    a = vorball.jfa(seeds, size=32, device="ref", variant="jfa,exact", check=True)
    assert untimed(f.to_json()) == untimed(json.loads(out))
    assert a.source == "points" and a.dim == 2
    for x, y in zip(f.runs, a.runs):
        assert np.array_equal(x.labels, y.labels)
    # The exact labels: the nearest seed of each pixel, ties to the lowest index.
    yy, xx = np.mgrid[0:32, 0:32]
    d = (xx[..., None] - seeds[:, 0]) ** 2 + (yy[..., None] - seeds[:, 1]) ** 2
    assert np.array_equal(a.runs[1].labels, np.argmin(d, axis=2))


def test_jfa_protein():
    pdb = corpus("data", "1crn.pdb")
    out, _ = cli("jfa", "--protein", pdb, "-n", "32", "--device", "ref", "-V", "exact", "--json")
    j = vorball.jfa(protein=pdb, size=32, device="ref", variant="exact")
    assert untimed(j.to_json()) == untimed(json.loads(out))
    assert j.dim == 3 and j.labels.shape == (32, 32, 32)
    assert j.seeds == len(vorball.read(pdb))


@pytest.mark.parametrize("kw, args", [
    ({"size": 1 << 15}, ["-n", str(1 << 15)]),
    ({"dim": 4}, ["-d", "4"]),
    ({"k": 0}, ["-k", "0"]),
    ({"margin": -1.0}, ["--margin", "-1"]),
    ({"m": 0}, ["-m", "0"]),
    ({"repeat": 0}, ["--repeat", "0"]),
    ({"variant": "jfa,nope"}, ["-V", "jfa,nope"]),
    ({"dist": "gauss"}, ["--dist", "gauss"]),
])
def test_jfa_refused_as_the_command(kw, args):
    _, err = cli("jfa", *args, rc=2)
    with pytest.raises(vorball.VorballError) as e:
        vorball.jfa(device="ref", **kw)
    assert e.value.number == 7
    # The command's message is the library's, with the value it was given.
    assert e.value.message in err
