"""The package installs with pip into a virtual environment made with --system-site-packages
(Debian's python refuses system-wide pip installs), downloading nothing, and works from there."""
import os
import subprocess
import sys

import pytest


def test_pip_install_into_a_venv(tmp_path):
    staged = os.environ.get("SPHD_PYTHON_PACKAGE")
    if not staged:
        pytest.skip("SPHD_PYTHON_PACKAGE is not set (run through ctest -L python)")
    venv = tmp_path / "venv"
    made = subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                          capture_output=True, text=True)
    if made.returncode != 0 and "ensurepip" in made.stdout + made.stderr:
        pytest.skip("python3-venv is not installed")
    assert made.returncode == 0, made.stdout + made.stderr
    pip = subprocess.run([str(venv / "bin" / "pip"), "install", "--no-build-isolation",
                          "--no-deps", "--no-index", staged], capture_output=True, text=True)
    assert pip.returncode == 0, pip.stdout + pip.stderr
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    check = subprocess.run(
        [str(venv / "bin" / "python"), "-c",
         "import sphd; print(sphd.__file__); print(sphd.Case(dx=0.1).dx)"],
        capture_output=True, text=True, env=env, cwd=tmp_path)
    assert check.returncode == 0, check.stderr
    print(check.stdout)
    assert str(venv) in check.stdout.splitlines()[0], "imported from elsewhere, not the venv"
    assert check.stdout.splitlines()[1] == "0.1"
