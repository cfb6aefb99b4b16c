"""The package as users get it: annotations that resolve, the version of
the C library, the installed copy with its own libvorball (the wheel to
hand on, in a fresh environment: test_wheel.py)."""
import inspect
import os
import re
import typing

import vorball

from conftest import ROOT, corpus


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
    # a Result, or with periodic=True / box= a PeriodicResult (issue 34)
    assert typing.get_type_hints(vorball.vertices)["return"] == \
        typing.Union[vorball.Result, vorball.PeriodicResult]
    assert typing.get_type_hints(vorball.Result)["certificate"] is vorball.Certificate
