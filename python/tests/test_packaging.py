"""The package as users get it: annotations that resolve, the version of
the C library, and a wheel built from the source tree that works in a
fresh environment outside the checkout (libvorball inside the wheel)."""
import glob
import inspect
import os
import re
import subprocess
import sys
import typing
import zipfile

import vorball

from conftest import BUILD, ROOT, cli, corpus


def test_version_is_the_libraries():
    cmake = open(os.path.join(ROOT, "CMakeLists.txt")).read()
    want = re.search(r"project\(vorball\s+VERSION\s+([0-9.]+)", cmake).group(1)
    assert vorball.__version__ == want


def test_installed_not_the_source_tree():
    """The tests run the installed package, its libvorball beside _core."""
    pkg = os.path.dirname(vorball.__file__)
    assert os.path.realpath(pkg) != os.path.realpath(os.path.join(ROOT, "python", "vorball"))
    assert os.path.exists(os.path.join(pkg, "py.typed"))
    vorball.vertices(corpus("inputs", "cubic_lattice.xyzr"), device="ref")
    maps = [line.split()[-1] for line in open("/proc/self/maps") if "libvorball.so" in line]
    assert maps and all(os.path.dirname(os.path.realpath(m)) == os.path.realpath(pkg)
                        for m in maps), maps


def public_callables():
    for name in vorball.__all__:
        obj = getattr(vorball, name)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj) and obj.__module__.startswith("vorball."):
            for mname, m in vars(obj).items():
                if inspect.isfunction(m) and (not mname.startswith("_") or mname == "__init__"):
                    yield "%s.%s" % (name, mname), m


def test_type_hints_resolve():
    """Every public function and method is annotated, and the annotations
    evaluate (PEP 561: py.typed ships with the package)."""
    seen = 0
    for name, f in public_callables():
        hints = typing.get_type_hints(f)
        params = [p for p in inspect.signature(f).parameters.values()
                  if p.name != "self" and p.kind is not p.VAR_POSITIONAL]
        missing = [p.name for p in params if p.name not in hints]
        assert not missing, (name, missing)
        assert "return" in hints, name
        seen += 1
    assert seen >= 20
    assert typing.get_type_hints(vorball.vertices)["return"] is vorball.Result
    assert typing.get_type_hints(vorball.Result)["certificate"] is vorball.Certificate


def test_wheel_from_the_source_tree(tmp_path):
    """pip wheel ./python: one wheel holding _core, libvorball.so.N and
    py.typed; installed into a folder of its own (pip --target) it
    computes the command's bytes, from a folder outside the checkout."""
    env = dict(os.environ, VORBALL_BUILD_DIR=BUILD)
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps",
                    "-q", "-w", str(tmp_path / "dist"), os.path.join(ROOT, "python")],
                   check=True, env=env, capture_output=True)
    wheels = glob.glob(str(tmp_path / "dist" / "vorball-*.whl"))
    assert len(wheels) == 1
    names = zipfile.ZipFile(wheels[0]).namelist()
    assert any(re.fullmatch(r"vorball/_core\..*\.so", n) for n in names), names
    assert any(re.fullmatch(r"vorball/libvorball\.so\.[0-9]+", n) for n in names), names
    assert "vorball/py.typed" in names
    meta = zipfile.ZipFile(wheels[0]).read(
        next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
    assert "Version: %s" % vorball.__version__ in meta and "Requires-Dist: numpy" in meta
    site = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "-q", "--no-deps", "--no-index",
                    "--target", str(site), wheels[0]], check=True, capture_output=True)
    path = corpus("inputs", "degree5_vertex.xyzr")
    code = ("import sys, vorball; print(vorball.__file__, file=sys.stderr); "
            "sys.stdout.write(vorball.vertices(sys.argv[1], device='ref').to_text())")
    # The wheel's copy comes first on the path (before the environment's).
    p = subprocess.run([sys.executable, "-c", code, path], capture_output=True, text=True,
                       cwd=str(tmp_path), env=dict(os.environ, PYTHONPATH=str(site)))
    assert p.returncode == 0, p.stderr
    assert p.stderr.startswith(str(site / "vorball")), p.stderr
    out, _ = cli("vertices", "--device", "ref", path)
    assert p.stdout == out
