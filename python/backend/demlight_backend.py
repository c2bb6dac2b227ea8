"""The PEP 517 build backend of `pip install .` and `pip wheel .` (pyproject.toml).

It needs only the standard library (pip's isolated build environment installs nothing, so it
works offline) and builds with the project's CMake the module `_demlight` for the interpreter
that runs it: CMake's FindPython is given `sys.executable`, pybind11 is Debian's
(pybind11-dev), only the module's target is built, in Release. The wheel is written here:
the package's Python files, the module, and a .dist-info folder (METADATA, WHEEL, RECORD), with
the tag of this interpreter and platform.

Where it builds:
- config setting `build-dir=DIR` (`pip install . -C build-dir=DIR`, pip >= 23.1; older pip:
  `--config-settings build-dir=DIR`): in DIR;
- otherwise in `build/release`, when that folder is configured with the Python package for an
  interpreter with this one's headers and module suffix (scripts/build.sh makes it so for
  /usr/bin/python3, and a venv made from it qualifies): the set-up's build is the wheel's, and
  nothing is compiled again;
- otherwise in `build/python-<tag>-<digest>` (one folder per interpreter installation, which
  its virtual environments share), configured on first use.
Every build runs on any x86-64 CPU (the vector code is picked when the program runs).
docs/python.md, "Installing with pip", says more.
"""

import ast
import base64
import hashlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig
import zipfile

SOURCE = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = "demlight"
# Zip entries carry this date, so that two builds of the same files are the same wheel.
ZIP_DATE = (1980, 1, 1, 0, 0, 0)


class BuildError(RuntimeError):
    pass


# ---- What the wheel is -----------------------------------------------------------------------

def _version():
    text = (SOURCE / "CMakeLists.txt").read_text()
    m = re.search(r"project\(\s*demlight\s+VERSION\s+([0-9][0-9.]*)", text)
    if not m:
        raise BuildError("CMakeLists.txt: no `project(demlight VERSION x.y.z ...)` to take the version from")
    return m.group(1)


def _project():
    """The [project] table of pyproject.toml, in the one-line forms it uses (`key = "text"`,
    `key = ["a", "b"]`): tomllib is not in the standard library before Python 3.11."""
    table, inside = {}, False
    for number, line in enumerate((SOURCE / "pyproject.toml").read_text().splitlines(), 1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if stripped.startswith("["):
            inside = stripped == "[project]"
            continue
        if not inside:
            continue
        key, sep, value = stripped.partition("=")
        try:
            parsed = ast.literal_eval(value.strip()) if sep else None
        except (ValueError, SyntaxError):
            parsed = None
        if not (isinstance(parsed, str) or (isinstance(parsed, list) and all(isinstance(v, str) for v in parsed))):
            raise BuildError("pyproject.toml line %d: the build backend reads `key = \"text\"` or "
                             "`key = [\"a\", ...]` on one line in [project], got: %s" % (number, stripped))
        table[key.strip()] = parsed
    return table


def _distribution():
    return "%s-%s" % (PACKAGE, _version())


def _tag():
    """This interpreter's wheel tag (as the `packaging` library spells it):
    interpreter-abi-platform, e.g. cp311-cp311-linux_x86_64."""
    version = "%d%d" % sys.version_info[:2]
    if sys.implementation.name == "cpython":
        interpreter = "cp" + version
        abi = interpreter + getattr(sys, "abiflags", "")
    else:
        interpreter = {"pypy": "pp"}.get(sys.implementation.name, sys.implementation.name) + version
        soabi = sysconfig.get_config_var("SOABI") or ""
        abi = re.sub(r"[-.]", "_", soabi) or "none"
    platform = re.sub(r"[-.]", "_", sysconfig.get_platform())
    if platform == "linux_x86_64" and sys.maxsize <= 2**32:  # a 32-bit interpreter on a 64-bit kernel
        platform = "linux_i686"
    return "%s-%s-%s" % (interpreter, abi, platform)


def _metadata():
    project = _project()
    lines = ["Metadata-Version: 2.1",
             "Name: %s" % project.get("name", PACKAGE),
             "Version: %s" % _version()]
    if "description" in project:
        lines.append("Summary: %s" % project["description"])
    if "requires-python" in project:
        lines.append("Requires-Python: %s" % project["requires-python"])
    lines += ["Requires-Dist: %s" % d for d in project.get("dependencies", [])]
    body = ""
    if "readme" in project:
        lines.append("Description-Content-Type: text/markdown")
        body = "\n" + (SOURCE / project["readme"]).read_text()
    return "\n".join(lines) + "\n" + body


def _wheel_file():
    return "Wheel-Version: 1.0\nGenerator: demlight_backend\nRoot-Is-Purelib: false\nTag: %s\n" % _tag()


def _write_dist_info(directory):
    dist_info = pathlib.Path(directory) / (_distribution() + ".dist-info")
    dist_info.mkdir(parents=True, exist_ok=True)
    (dist_info / "METADATA").write_text(_metadata())
    (dist_info / "WHEEL").write_text(_wheel_file())
    return dist_info.name


# ---- Building the module ---------------------------------------------------------------------

def _include_dir():
    return os.path.realpath(sysconfig.get_paths()["include"])


def _module_name():
    return "_demlight" + sysconfig.get_config_var("EXT_SUFFIX")


def _cache(build_dir):
    """CMakeCache.txt of `build_dir` as name -> value, or {} when it is not configured."""
    try:
        text = (build_dir / "CMakeCache.txt").read_text()
    except OSError:
        return {}
    out = {}
    for line in text.splitlines():
        m = re.match(r"([^#/][^:=]*):[A-Z]+=(.*)$", line)
        if m:
            out[m.group(1)] = m.group(2)
    return out


def _fits_this_interpreter(cache):
    """Whether a configured build makes the module for this interpreter: the Python package on,
    Release, and FindPython's headers and module suffix (SOABI) those of this interpreter."""
    soabi = sysconfig.get_config_var("SOABI") or ""
    properties = cache.get("_Python_INTERPRETER_PROPERTIES", "").split(";")
    include = cache.get("_Python_INCLUDE_DIR", "")
    return (cache.get("DEMLIGHT_PYTHON") in ("ON", "TRUE", "1") and cache.get("CMAKE_BUILD_TYPE") == "Release"
            and bool(include) and os.path.realpath(include) == _include_dir() and soabi in properties)


def _setting(config_settings, key):
    value = (config_settings or {}).get(key)
    if isinstance(value, list):  # given twice
        value = value[-1]
    return value


def _build_dir(config_settings):
    given = _setting(config_settings, "build-dir")
    if given:
        return pathlib.Path(given).resolve()
    release = SOURCE / "build" / "release"
    if _fits_this_interpreter(_cache(release)):
        return release
    installation = "%s\n%s" % (_include_dir(), os.path.realpath(sys.base_prefix))
    digest = hashlib.sha256(installation.encode()).hexdigest()[:10]
    # Beside build/release, at the same depth: with ccache's base directory the source tree,
    # the compile commands are the same and the set-up's objects are reused.
    return SOURCE / "build" / ("python-%s-%s" % (_tag(), digest))


def _run(command):
    print("demlight_backend: " + " ".join(command), file=sys.stderr, flush=True)
    env = dict(os.environ)
    env.setdefault("CCACHE_BASEDIR", str(SOURCE))  # compile commands relative to the tree (ccache)
    if subprocess.run(command, stdout=sys.stderr, env=env).returncode != 0:
        raise BuildError("failed: " + " ".join(command))


def _build(config_settings):
    """Builds the module and the package's files; returns the folder that holds them."""
    cmake = shutil.which("cmake")
    if not cmake:
        raise BuildError("cmake not found: install the build dependencies (scripts/install-deps.sh)")
    build_dir = _build_dir(config_settings)
    cache = _cache(build_dir)
    # The set-up's build (scripts/build.sh) is used as it is; any other folder is configured
    # for this interpreter (a venv's path may have changed since the last run).
    if not (build_dir == SOURCE / "build" / "release" and _fits_this_interpreter(cache)):
        configure = [cmake, "-S", str(SOURCE), "-B", str(build_dir)]
        if not cache:
            if shutil.which("ninja"):
                configure += ["-G", "Ninja"]
            configure += ["-DDEMLIGHT_BUILD_TESTS=OFF", "-DDEMLIGHT_FUZZ=OFF"]
        configure += ["-DCMAKE_BUILD_TYPE=Release", "-DDEMLIGHT_PYTHON=ON", "-DPython_EXECUTABLE=" + sys.executable]
        _run(configure)
        if not _fits_this_interpreter(_cache(build_dir)):
            raise BuildError("%s: CMake found another Python than %s" % (build_dir, sys.executable))
    _run([cmake, "--build", str(build_dir), "--target", "_demlight"])
    package = build_dir / "python" / PACKAGE
    if not (package / _module_name()).is_file():
        raise BuildError("the build made no %s in %s" % (_module_name(), package))
    return package


# ---- Wheels ----------------------------------------------------------------------------------

def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def _write_wheel(wheel_directory, files):
    """A wheel of `files` (name in the wheel -> bytes, executable flag) with its .dist-info."""
    distribution = _distribution()
    dist_info = distribution + ".dist-info"
    entries = dict(files)
    entries[dist_info + "/METADATA"] = (_metadata().encode(), False)
    entries[dist_info + "/WHEEL"] = (_wheel_file().encode(), False)
    record = [_record_line(name, data) for name, (data, _) in entries.items()]
    record.append(dist_info + "/RECORD,,")
    entries[dist_info + "/RECORD"] = (("\n".join(record) + "\n").encode(), False)
    name = "%s-%s.whl" % (distribution, _tag())
    path = pathlib.Path(wheel_directory) / name
    partial = path.with_name(name + ".part")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED) as wheel:
        for entry, (data, executable) in entries.items():
            info = zipfile.ZipInfo(entry, ZIP_DATE)
            info.external_attr = (0o755 if executable else 0o644) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(info, data)
    os.replace(partial, path)
    return name


def _package_files(package):
    """The package's Python files (from the source tree) and the module built for this
    interpreter (from the build), as wheel entries."""
    files = {}
    for source in sorted((SOURCE / "python" / PACKAGE).glob("*.py")):
        files["%s/%s" % (PACKAGE, source.name)] = (source.read_bytes(), False)
    module = package / _module_name()
    files["%s/%s" % (PACKAGE, module.name)] = (module.read_bytes(), True)
    return files


# ---- PEP 517 and PEP 660 hooks ---------------------------------------------------------------

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_editable(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    return _write_dist_info(metadata_directory)


def prepare_metadata_for_build_editable(metadata_directory, config_settings=None):
    return _write_dist_info(metadata_directory)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    return _write_wheel(wheel_directory, _package_files(_build(config_settings)))


def build_editable(wheel_directory, config_settings=None, metadata_directory=None):
    """`pip install -e .`: a wheel holding one .pth that names the build's python/ folder (the
    package's Python files are copied there by the build: rebuild after editing them)."""
    package = _build(config_settings)
    pth = (str(package.parent) + "\n").encode()
    return _write_wheel(wheel_directory, {"_demlight_editable.pth": (pth, False)})
