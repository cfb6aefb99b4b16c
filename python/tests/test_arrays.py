"""NumPy inputs of every dtype and layout: each element becomes one exact
decimal by a documented rule, or is refused with a numbered error."""
import decimal

import numpy as np
import pytest
import vorball

from conftest import cli, corpus

CASE = corpus("inputs", "crambin_fragment.xyzr")


@pytest.fixture(scope="module")
def frag():
    s = vorball.read(CASE)
    return s, vorball.vertices(s, device="ref").to_text()


def dec(s):
    return s.decimals


def test_layouts_same_vertices(frag):
    """C order, Fortran order, a strided view, byte-swapped, (n, 4)."""
    s, want = frag
    xyzr = np.column_stack([s.xyz, s.r])
    big = np.zeros((2 * s.n, 8))
    big[::2, 1:8:2] = xyzr  # every other row, every other column
    variants = {
        "C": (np.ascontiguousarray(s.xyz), s.r),
        "F": (np.asfortranarray(s.xyz), s.r),
        "strided": (big[::2, 1:6:2], big[::2, 7]),
        "byteswapped": (s.xyz.astype(">f8"), s.r.astype(">f8")),
        "xyzr": (xyzr, None),
        "lists": (s.xyz.tolist(), s.r.tolist()),
    }
    assert not variants["strided"][0].flags.c_contiguous
    for name, (x, r) in variants.items():
        assert vorball.vertices(x, r, device="ref").to_text() == want, name


def test_float64_is_its_repr():
    v = np.array([0.1, 1 / 3, -2.5e-7, 123456.789, 2.0**-30, 1e9, -0.0])
    s = vorball.spheres(np.column_stack([v, v, v]), np.full(v.size, 1.5))
    assert [d for d in dec(s)[:, 0]] == [decimal.Decimal(repr(float(x))) for x in v]
    # 0.1 is the decimal 0.1, not the binary fraction nearest it.
    assert dec(s)[0, 0] == decimal.Decimal("0.1")


def test_float32_is_its_shortest_decimal():
    rng = np.random.default_rng(7)
    v = np.concatenate([
        rng.uniform(-1000, 1000, 3000).astype(np.float32),
        (rng.standard_normal(2000) * 10.0 ** rng.integers(-30, 9, 2000)).astype(np.float32),
        np.float32(2.0) ** np.arange(-126, 29, dtype=np.float32),   # powers of two
        np.array([1e-45, 1.4e-45, 3.4e38 / 1e30, 16777216, 16777217, 0.1, 1.1, 9999.999,
                  -999.999, 12.345], dtype=np.float32),
    ])
    v = np.unique(v[(np.abs(v) <= 1e9) & (v != 0)])
    s = vorball.spheres(np.column_stack([v, v, v]), np.full(v.size, np.float32(1.5)))
    got = dec(s)[:, 0]
    want = [decimal.Decimal(str(x)) for x in v]  # numpy's shortest round-trip float32
    bad = [(x, g, w) for x, g, w in zip(v, got, want) if g != w]
    assert not bad, bad[:5]
    # Each decimal reads back as the float32 it came from.
    assert all(np.float32(float(g)) == x for g, x in zip(got, v))


def test_integers_exact():
    for dt in (np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64):
        xyz = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [4, 4, 4]], dtype=dt)
        s = vorball.spheres(xyz, np.array([1, 1, 2, 1, 1], dtype=dt))
        assert dec(s)[4].tolist() == [4, 4, 4, 1], dt
        assert s.xyz.dtype == np.float64 and s.xyz[1, 0] == 4.0


def test_strings_and_decimals_verbatim(frag):
    s, want = frag
    d = s.decimals
    # str and Decimal arrays give the file's decimals: the same vertices.
    assert vorball.vertices(d[:, :3], d[:, 3], device="ref").to_text() == want
    assert vorball.vertices(d[:, :3].astype(str), d[:, 3].astype(str), device="ref").to_text() \
        == want
    # 17 significant digits kept exactly (no double in between).
    x = vorball.spheres(np.array([["0.12345678901234567", "0", "0"]]), ["1"])
    assert x.decimals[0, 0] == decimal.Decimal("0.12345678901234567")


def test_mixed_dtypes_per_column():
    xyz = np.zeros((5, 3), dtype=object)
    xyz[:, 0] = [0, 4, 0, 0, 4]
    xyz[:, 1] = [np.float32(0), np.float32(0), np.float32(4.5), np.float32(0), np.float32(4)]
    xyz[:, 2] = [decimal.Decimal("0"), 0.0, "0", 4, "4.25"]
    s = vorball.spheres(xyz, 1)
    assert dec(s)[4, :3].tolist() == [4, 4, decimal.Decimal("4.25")]


def test_scalar_radius():
    s = vorball.spheres(np.eye(4, 3) * 3, 1.25)
    assert np.array_equal(s.r, np.full(4, 1.25))


@pytest.mark.parametrize("dtype", [np.float16, np.longdouble, np.bool_, np.complex128,
                                   "datetime64[s]"])
def test_refused_dtypes(dtype):
    xyz = np.zeros((4, 3)).astype(dtype)
    with pytest.raises(vorball.VorballError) as e:
        vorball.spheres(xyz, 1.0)
    assert e.value.number == 7 and e.value.exit_status == 2
    assert "dtype" in str(e.value) or "float" in str(e.value)


@pytest.mark.parametrize("xyz,r", [
    (np.zeros((4, 2)), 1.0), (np.zeros(12), 1.0), (np.zeros((4, 3)), np.ones(3)),
    (np.zeros((4, 3)), None), (np.zeros((4, 4)), 1.0)])
def test_refused_shapes(xyz, r):
    with pytest.raises(vorball.VorballError) as e:
        vorball.spheres(xyz, r)
    assert e.value.number == 7


def test_masked_values_refused():
    xyz = np.ma.masked_array(np.eye(4, 3), mask=np.zeros((4, 3), bool))
    assert len(vorball.spheres(xyz, 1.0)) == 4  # nothing masked: fine
    xyz.mask[2, 1] = True
    with pytest.raises(vorball.VorballError, match="masked"):
        vorball.spheres(xyz, 1.0)


def rows_error(xyz, r, number, row, **kw):
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(xyz, r, device="ref", **kw)
    assert e.value.number == number, e.value
    assert e.value.row == row, e.value
    return e.value


def test_bad_values_name_their_row():
    xyz = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [4, 4, 4]], dtype=float)
    r = np.ones(5)
    bad = xyz.copy()
    bad[3, 1] = np.nan
    rows_error(bad, r, 102, 3)
    rr = r.copy()
    rr[2] = -1
    rows_error(xyz, rr, 103, 2)
    rr[2] = 0
    e = rows_error(xyz, rr, 103, 2)
    assert "zero" in e.message  # the remedy is named (zero_radius=point)
    assert len(vorball.vertices(xyz, rr, device="ref", zero_radius="point").t) >= 0
    dup = xyz.copy()
    dup[4] = dup[1]
    rows_error(dup, r, 104, 4)
    big = xyz.copy()
    big[1, 0] = 2e9
    rows_error(big, r, 107, 1)
    s = xyz.astype(str)
    s[2, 2] = "1 2"
    rows_error(s, r, 101, 2)
    s[2, 2] = "0.1234567890123456789"  # 19 significant digits
    rows_error(s, r, 107, 2)


def test_too_few_and_empty():
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(np.eye(3), np.ones(3), device="ref")
    assert e.value.number == 106 and e.value.exit_status == 16
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(np.zeros((0, 3)), np.zeros(0), device="ref")
    assert e.value.number == 105


def test_exit_status_is_the_commands(tmp_path):
    """The same input as a file: the command exits with the error's status."""
    xyz = np.array([[0, 0, 0], [4, 0, 0], [0, 4, 0], [4, 0, 0]], dtype=float)
    with pytest.raises(vorball.VorballError) as e:
        vorball.vertices(xyz, np.ones(4), device="ref")
    p = tmp_path / "dup.xyzr"
    p.write_text("".join("%r %r %r 1\n" % tuple(v) for v in xyz.tolist()))
    _, err = cli("vertices", "--device", "ref", p, rc=e.value.exit_status)
    assert ("E%d:" % e.value.number) in err
