"""demlight installed as users install Python packages: `pip install .` and `pip wheel .` (the
in-tree build backend of pyproject.toml) into fresh virtual environments with no package index,
then the README's example; and the import errors of a module that cannot work (no numpy, a
module built for another Python)."""

import base64
import csv
import hashlib
import io
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import zipfile

import pytest

from conftest import REPO

# Debian's interpreter, which the set-up command builds for (a pyenv python3 may come first on PATH).
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


def environment():
    """The environment of a user's shell: no PYTHONPATH (the set-up's .pth stays, as it is in
    /usr/bin/python3's site-packages), no pip version check, no index (offline)."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env.update(PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_INDEX="1", PYTHONDONTWRITEBYTECODE="1")
    return env


def run(*args, cwd=None, check=True, timeout=900):
    out = subprocess.run([str(a) for a in args], cwd=cwd, env=environment(), capture_output=True, text=True,
                         timeout=timeout)
    if check and out.returncode != 0:
        raise AssertionError("%s failed (%d):\n%s\n%s" % (" ".join(map(str, args)), out.returncode, out.stdout[-3000:],
                                                         out.stderr[-3000:]))
    return out


def venv(path, *options, python=PYTHON):
    run(python, "-m", "venv", *options, path)
    return pathlib.Path(path) / "bin" / "python"


def readme_example(tmp_path):
    readme = (REPO / "README.md").read_text()
    block = re.search(r"```python\n(.*?)```", readme, re.S)
    assert block, "README.md has no ```python example"
    return block.group(1).replace("x.tif", str(tmp_path / "x.tif"))


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    """`pip wheel .` by Debian's interpreter, offline."""
    out = tmp_path_factory.mktemp("wheels")
    run(PYTHON, "-m", "pip", "wheel", "--no-deps", "--no-index", "-w", out, REPO)
    wheels = list(out.glob("*.whl"))
    assert len(wheels) == 1, wheels
    return wheels[0]


def test_pip_install_into_a_fresh_venv_runs_the_readme_example(tmp_path):
    # "Neither 'setup.py' nor 'pyproject.toml' found" before; with pip's build isolation (the
    # backend asks for nothing, so no index is needed).
    python = venv(tmp_path / "venv", "--system-site-packages")
    run(python, "-m", "pip", "install", "--no-index", REPO)
    where = run(python, "-c", "import demlight; print(demlight.__file__)", cwd=tmp_path).stdout.strip()
    assert where.startswith(str(tmp_path / "venv")), where  # the venv's, not the set-up's .pth
    out = run(python, "-c", readme_example(tmp_path), cwd=REPO)
    assert "sun_visibility" in out.stdout
    assert (tmp_path / "x.tif").exists()


def test_pip_wheel_installs_in_another_venv(tmp_path, wheel):
    tag = "cp%d%d-cp%d%d%s-%s" % (sys.version_info[:2] + sys.version_info[:2] + (sys.abiflags,) +
                                  (re.sub(r"[-.]", "_", sysconfig.get_platform()),))
    if PYTHON == sys.executable:
        assert wheel.name.endswith(tag + ".whl"), wheel.name
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        version = re.search(r"project\(demlight VERSION ([0-9.]+)", (REPO / "CMakeLists.txt").read_text()).group(1)
        dist_info = "demlight-%s.dist-info/" % version
        metadata = z.read(dist_info + "METADATA").decode()
        assert "\nName: demlight\n" in metadata and "\nVersion: %s\n" % version in metadata
        assert "\nRequires-Dist: numpy\n" in metadata and "\nRequires-Python: >=3.9\n" in metadata
        assert "Root-Is-Purelib: false" in z.read(dist_info + "WHEEL").decode()
        # Every file is in RECORD with its hash and size, as pip checks.
        record = list(csv.reader(io.StringIO(z.read(dist_info + "RECORD").decode())))
        assert sorted(r[0] for r in record) == sorted(names)
        for name, digest, size in record:
            if name.endswith("RECORD"):
                continue
            data = z.read(name)
            assert digest == "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            assert int(size) == len(data)
        assert {"demlight/__init__.py", "demlight/dask.py"} <= set(names)
        assert any(re.fullmatch(r"demlight/_demlight\..*\.so", n) for n in names), names
    python = venv(tmp_path / "other", "--system-site-packages")
    run(python, "-m", "pip", "install", "--no-index", wheel)
    out = run(python, "-c", "import demlight; r = demlight.sky(%r, srcwin=(0, 0, 20, 20)); print(demlight.__file__, "
                            "list(r.bands))" % str(REPO / "samples" / "rocky_mountain_np_dem.tif"), cwd=tmp_path)
    assert out.stdout.startswith(str(tmp_path / "other")) and "sky_K" in out.stdout, out.stdout


def test_the_backend_reads_pyproject_as_tomllib_does():
    tomllib = pytest.importorskip("tomllib")
    sys.path.insert(0, str(REPO / "python" / "backend"))
    try:
        import demlight_backend
    finally:
        sys.path.pop(0)
    with open(REPO / "pyproject.toml", "rb") as f:
        declared = tomllib.load(f)
    assert declared["build-system"]["requires"] == []
    assert demlight_backend._project() == declared["project"]


def test_without_numpy_the_import_names_numpy(tmp_path, wheel):
    # It imported, computed, and failed only on r.bands with "No module named 'numpy'".
    python = venv(tmp_path / "bare")  # no system site-packages: no numpy
    run(python, "-m", "pip", "install", "--no-index", "--no-deps", wheel)
    out = run(python, "-c", "import demlight", cwd=tmp_path, check=False)
    assert out.returncode != 0
    last = out.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: demlight needs numpy") and "pip install numpy" in last, out.stderr


def test_a_module_built_for_another_python_names_both_versions(tmp_path):
    # "cannot import name '_demlight' from partially initialized module 'demlight' (most likely
    # due to a circular import)" before. The package's module renamed to another version's name:
    package = tmp_path / "demlight"
    shutil.copytree(REPO / "python" / "demlight", package)
    shutil.copy(REPO / "build" / "release" / "python" / "demlight" / ("_demlight" + sysconfig.get_config_var("EXT_SUFFIX")),
                package / "_demlight.cpython-39-x86_64-linux-gnu.so")
    out = subprocess.run([sys.executable, "-c", "import demlight"], cwd=tmp_path, capture_output=True, text=True,
                         env=dict(environment(), PYTHONPATH=str(tmp_path)))
    assert out.returncode != 0
    last = out.stderr.strip().splitlines()[-1]
    assert "was built for Python 3.9 (_demlight.cpython-39-x86_64-linux-gnu.so)" in last, out.stderr
    assert "this is Python %d.%d" % sys.version_info[:2] in last and "pip install ." in last, out.stderr
    assert "circular" not in out.stderr


def other_interpreters():
    """Pythons 3.9+ of another minor version than Debian's on this machine (pyenv's)."""
    root = pathlib.Path(os.environ.get("PYENV_ROOT", pathlib.Path.home() / ".pyenv")) / "versions"
    found = {}
    for python in sorted(root.glob("3.*/bin/python3")):
        m = re.match(r"3\.(\d+)\.", python.parent.parent.name)
        if m and int(m.group(1)) >= 9 and int(m.group(1)) != sys.version_info[1]:
            found.setdefault(int(m.group(1)), python)
    return list(found.values())


@pytest.mark.parametrize("python", other_interpreters() or [pytest.param(None, marks=pytest.mark.skip(
    reason="no other Python 3.9+ on this machine (pyenv)"))])
def test_the_set_up_build_in_another_python_names_its_version(python):
    # The set-up's module is Debian's Python's; pyenv's python3 on PATH imported it through the
    # PYTHONPATH that docs/python.md gave and failed with the circular-import message.
    out = subprocess.run([str(python), "-c", "import demlight"], capture_output=True, text=True, cwd="/",
                         env=dict(environment(), PYTHONPATH=str(REPO / "build" / "release" / "python")))
    assert out.returncode != 0
    last = out.stderr.strip().splitlines()[-1]
    assert "was built for Python %d.%d" % sys.version_info[:2] in last, out.stderr
    assert "this is Python 3." in last and str(python) in last, out.stderr
