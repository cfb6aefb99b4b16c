"""The Python example of README.md runs as written from the repository root
and prints what the comments of its print lines say."""
import os
import re
import subprocess
import sys

from conftest import ROOT


def readme_python_block():
    """The README's code block that starts with 'import vorball'."""
    lines = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read().splitlines()
    start = lines.index("    import vorball")
    block = []
    for line in lines[start:]:
        if not line.startswith("    "):
            break
        block.append(line[4:])
    return block


def test_readme_python_example():
    block = readme_python_block()
    expected = [re.search(r"#\s*(.*?)\s*$", l).group(1) for l in block if l.startswith("print(")]
    assert len(expected) >= 2, "the README example prints nothing to check"
    p = subprocess.run([sys.executable, "-c", "\n".join(block)], cwd=ROOT, capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines() == expected
