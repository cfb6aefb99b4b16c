"""The wheel to hand to a colleague (python/wheel.sh, python/README.md):
built once from the existing CMake tree, installed with pip --no-deps
--no-index into a fresh virtual environment that has NumPy and nothing of
vorball, and run from a folder outside the checkout: the command's bytes,
with libvorball and the bundled GMP, MPFR and OpenCL loader loaded from the
wheel's own folders."""
import glob
import os
import re
import subprocess
import sys
import time
import zipfile

import pytest

import vorball

from conftest import BUILD, ROOT, cli, corpus

# What the fresh environment's Python loads, from the environment's site-packages.
PROBE = r"""
import json, sys, vorball
r = vorball.vertices(sys.argv[1], device=sys.argv[2])
maps = sorted({l.split()[-1] for l in open("/proc/self/maps")
               if "vorball" in l and ".so" in l})
json.dump({"file": vorball.__file__, "version": vorball.__version__, "text": r.to_text(),
           "maps": maps}, sys.stdout)
"""


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    out = tmp_path_factory.mktemp("dist")
    t = time.monotonic()
    p = subprocess.run(["bash", os.path.join(ROOT, "python", "wheel.sh"), str(out)],
                       env=dict(os.environ, VORBALL_BUILD_DIR=BUILD), capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stdout + p.stderr
    wheels = glob.glob(str(out / "vorball-*.whl"))
    assert len(wheels) == 1, wheels
    print("wheel %s: %d bytes, built in %.1f s" % (os.path.basename(wheels[0]),
                                                   os.path.getsize(wheels[0]),
                                                   time.monotonic() - t))
    assert p.stdout.strip() == wheels[0]
    return wheels[0]


@pytest.fixture(scope="module")
def venv(wheel, tmp_path_factory):
    """A fresh environment (Debian's NumPy through --system-site-packages)
    with the wheel installed: (python, site-packages)."""
    where = tmp_path_factory.mktemp("venv")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(where / "v")],
                   check=True, env=env)
    py = str(where / "v" / "bin" / "python")
    before = subprocess.run([py, "-c", "import vorball"], capture_output=True, text=True,
                            cwd=str(where), env=env)
    assert before.returncode != 0 and "No module named 'vorball'" in before.stderr
    t = time.monotonic()
    subprocess.run([py, "-m", "pip", "install", "-q", "--no-deps", "--no-index", wheel],
                   check=True, capture_output=True, env=env)
    print("installed into a fresh venv in %.1f s" % (time.monotonic() - t))
    site = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"],
                          check=True, capture_output=True, text=True, env=env).stdout.strip()
    return py, site, str(where), env


def test_wheel_contents(wheel):
    """manylinux tag of this CPython; _core, libvorball.so.0, py.typed and
    the system libraries libvorball needs, renamed by auditwheel."""
    tag = "cp%d%d" % sys.version_info[:2]
    assert re.fullmatch(r"vorball-%s-%s-%s-manylinux_2_[0-9]+_x86_64\.whl" % (
        re.escape(vorball.__version__), tag, tag), os.path.basename(wheel)), wheel
    z = zipfile.ZipFile(wheel)
    names = z.namelist()
    for want in (r"vorball/_core\..*\.so", r"vorball/libvorball\.so\.[0-9]+", r"vorball/py\.typed",
                 r"vorball\.libs/libgmp-[0-9a-f]+\.so\..*", r"vorball\.libs/libmpfr-[0-9a-f]+\.so\..*",
                 r"vorball\.libs/libOpenCL-[0-9a-f]+\.so\..*"):
        assert any(re.fullmatch(want, n) for n in names), (want, names)
    # PoCL is a driver: the target's, never the wheel's.
    assert not any("pocl" in n.lower() for n in names), names
    meta = z.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
    assert "Version: %s" % vorball.__version__ in meta and "Requires-Dist: numpy" in meta


@pytest.mark.parametrize("device,path", [("ref", ("data", "1crn.pdb")),
                                         ("cpu", ("inputs", "degree5_vertex.xyzr"))])
def test_fresh_venv_outside_the_checkout(venv, device, path):
    """The installed wheel gives the command's bytes from a folder outside
    the checkout; its libraries are its own (libvorball beside _core, GMP,
    MPFR and the ICD loader in vorball.libs), and the OpenCL device (cpu:
    PoCL) is found by the bundled loader."""
    import json
    py, site, where, env = venv
    path = corpus(*path)
    assert not os.path.realpath(where).startswith(os.path.realpath(ROOT) + os.sep)
    p = subprocess.run([py, "-c", PROBE, path, device], capture_output=True, text=True,
                       cwd=where, env=env)
    assert p.returncode == 0, p.stderr
    got = json.loads(p.stdout)
    assert got["file"] == os.path.join(site, "vorball", "__init__.py")
    assert got["version"] == vorball.__version__
    out, _ = cli("vertices", "--device", device, path)
    assert got["text"] == out and out.count("\tcertified") > 10
    maps = got["maps"]
    for lib in ("vorball/libvorball.so.0", "vorball.libs/libgmp-", "vorball.libs/libmpfr-",
                "vorball.libs/libOpenCL-"):
        assert any(m.startswith(os.path.join(site, lib)) for m in maps), (lib, maps)
