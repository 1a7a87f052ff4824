"""docs/python.md, run: its python blocks in order, in one namespace, against a real server and
pool, in a folder that sees the repository's cases/ and tests/ (the tutorial's paths are
relative to the repository root). The tutorial checks its own numbers (the front's deviation
from the MPS reference against docs/accuracy.md)."""
import os
import re

from conftest import ROOT


def python_blocks(path):
    with open(path, encoding="utf-8") as f:
        return re.findall(r"^```python\n(.*?)^```", f.read(), re.S | re.M)


def test_tutorial(service, tmp_path, monkeypatch):
    for name in ("cases", "tests"):
        os.symlink(os.path.join(ROOT, name), tmp_path / name)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("SPHCTL_SERVER", service.address)
    blocks = python_blocks(os.path.join(ROOT, "docs", "python.md"))
    assert len(blocks) >= 5
    namespace = {}
    for k, code in enumerate(blocks):
        exec(compile(code, f"docs/python.md block {k + 1}", "exec"), namespace)
    assert os.path.getsize("dambreak_front.png") > 10000
    assert namespace["result"].meta["status"]
