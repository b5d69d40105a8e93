"""Find a Python that has the modules a script needs (h5py, numpy, matplotlib, vtk).

The first python3 on PATH may be a pyenv, conda or venv interpreter without h5py. A script calls
ensure(...) before importing them: if this interpreter lacks one and Debian's /usr/bin/python3 has
them all, the script is run again with it (once, said on stderr); otherwise it stops with the
packages to install.
"""
import importlib.util
import os
import subprocess
import sys

DEBIAN_PYTHON = "/usr/bin/python3"
DEBIAN_PACKAGES = {"h5py": "python3-h5py", "numpy": "python3-numpy", "matplotlib": "python3-matplotlib", "vtk": "python3-vtk9"}
_GUARD = "DEM_PYTHON_RERUN"


def _missing(modules):
    return [m for m in modules if importlib.util.find_spec(m) is None]


def ensure(*modules: str) -> None:
    lacking = _missing(modules)
    if not lacking:
        return
    name = os.path.basename(sys.argv[0]) or "script"
    if os.environ.get(_GUARD) is None and os.access(DEBIAN_PYTHON, os.X_OK):
        probe = "import importlib.util, sys; sys.exit(any(importlib.util.find_spec(m) is None for m in sys.argv[1:]))"
        if subprocess.run([DEBIAN_PYTHON, "-c", probe, *modules], capture_output=True).returncode == 0:
            print(f"{name}: {sys.executable} lacks {', '.join(lacking)}; running with {DEBIAN_PYTHON}", file=sys.stderr)
            sys.stderr.flush()
            os.environ[_GUARD] = "1"
            os.execv(DEBIAN_PYTHON, [DEBIAN_PYTHON, sys.argv[0], *sys.argv[1:]])
    packages = " ".join(DEBIAN_PACKAGES.get(m, "python3-" + m) for m in lacking)
    sys.exit(f"{name}: error: the Python modules {', '.join(lacking)} are missing from {sys.executable}"
             f"{' and from ' + DEBIAN_PYTHON if os.access(DEBIAN_PYTHON, os.X_OK) and sys.executable != DEBIAN_PYTHON else ''}. "
             f"On Debian or Ubuntu: apt-get install {packages} (then run the script with {DEBIAN_PYTHON}); "
             f"or, in this Python's environment: python3 -m pip install {' '.join(lacking)}")
