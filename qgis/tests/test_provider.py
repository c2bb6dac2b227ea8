"""Tests of the QGIS Processing provider (qgis/demlight_processing, docs/qgis.md).

The first tests need only the CLI: its option description, progress lines and cancellation as
the provider reads them. The rest run qgis_process headless on an isolated QGIS profile (a
temporary QGIS_CUSTOM_CONFIG_PATH, never the user's) and compare its outputs with the CLI's;
they skip, saying so, when qgis_process or python3-qgis is missing.
Run: python3 -m pytest -q qgis/tests (scripts/test.sh does)."""

import hashlib
import json
import re
import os
import shutil
import shlex
import subprocess
import sys
import tempfile

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "qgis"))
from demlight_processing import cli  # noqa: E402  (no QGIS import in this module)

SAMPLE = os.path.join(REPO, "samples", "mount_st_helens_1980_usgs.dem")
TIME, TZ = "2024-06-21T07:30", "America/Los_Angeles"


def demlight_executable():
    path = os.environ.get(cli.EXECUTABLE_ENV) or os.path.join(REPO, "build", "release", "cli", "demlight")
    if not os.access(path, os.X_OK):
        pytest.skip(f"no demlight CLI at {path}: build it (scripts/build.sh) or set {cli.EXECUTABLE_ENV}")
    return path


def qgis_process_program():
    # Debian 12's /usr/bin/qgis_process wrapper passes --noversioncheck, which qgis_process 3.22
    # rejects as an unknown command (a known QGIS bug, github.com/qgis/QGIS #57683); the program it
    # wraps works.
    return shutil.which("qgis_process.bin") or shutil.which("qgis_process")


def values_digest(path):
    """SHA-256 of every band's stored values (gdal_translate to raw ENVI bytes): gdalinfo's
    checksum rounds floating-point values to whole numbers, so only the bytes show two rasters
    are the same bit for bit."""
    with tempfile.TemporaryDirectory() as scratch:
        raw = os.path.join(scratch, "values.bin")
        subprocess.run(["gdal_translate", "-q", "-of", "ENVI", str(path), raw], check=True, capture_output=True)
        with open(raw, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()


def checksums(path):
    """What must match between the CLI's and the provider's rasters: each band's checksum,
    type, description, nodata and metadata, the georeference, and the DEMLIGHT_* metadata but
    DEMLIGHT_COMMAND (the command line, which names the output path)."""
    info = json.loads(subprocess.run(["gdalinfo", "-json", "-checksum", path], capture_output=True, text=True,
                                     check=True).stdout)
    metadata = dict(info.get("metadata", {}).get("", {}))
    metadata.pop("DEMLIGHT_COMMAND")
    bands = [{k: b.get(k) for k in ("checksum", "type", "description", "noDataValue", "metadata")}
             for b in info["bands"]]
    return {"values": values_digest(path), "size": info["size"], "geoTransform": info["geoTransform"],
            "crs": info["coordinateSystem"]["wkt"], "metadata": metadata, "bands": bands}


# ---- the CLI as the provider reads it ---------------------------------------------------------

def test_options_describe_every_raster_command_with_its_help():
    description = cli.load_commands(demlight_executable())
    commands = {c["name"]: c for c in description["commands"]}
    assert "options" not in commands  # hidden: it describes the others
    help_text = subprocess.run([demlight_executable(), "sun", "--help"], capture_output=True, text=True,
                               check=True).stdout
    assert commands["sun"]["help"] == help_text
    assert (commands["sun"]["output"], commands["horizon"]["output"]) == ("raster", "raster")
    assert (commands["timelapse"]["output"], commands["render"]["output"]) == ("folder", "picture")
    assert commands["horizon"]["companions"] == ["DEMLIGHT_TRUNCATION_MASK"]
    assert commands["info"]["output"] is None
    options = {o["name"]: o for o in commands["sun"]["options"]}
    assert options["time"]["required"] and options["time"]["flags"] == ["--time"]
    assert options["quality"]["choices"] == ["auto", "full"] and options["quality"]["default"] == "auto"
    assert options["sun_diameter"]["type"] == "FLOAT" and float(options["sun_diameter"]["default"]) > 0
    assert options["sun_diameter"]["label"] == "Sun diameter (deg)" and options["sun_diameter"]["unit"] == "deg"
    assert options["sun_diameter"]["range"] == {"min": 0, "max": 20, "min_open": False}
    assert options["creation_options"]["flags"] == ["--co"] and options["creation_options"]["max_values"] == -1
    assert options["srcwin"]["min_values"] == 4 and options["srcwin"]["advanced"]
    assert options["verbose"]["flag"] and options["verbose"]["front_ends"] == ["cli"]
    assert options["dem"]["positional"] and options["dem"]["front_ends"] == ["cli", "qgis"]
    assert options["max_distance"]["qgis_help"].count('"Quality"') == 1


def test_progress_lines_are_read_and_cancel_stops_the_cli(tmp_path):
    out = tmp_path / "h.tif"
    seen = []
    # The brute-force reference takes seconds on the sample; cancel at its first progress line.
    code, messages = cli.run([demlight_executable(), "horizon", SAMPLE, "-o", str(out), "--directions", "8",
                              "--method", "reference"],
                             lambda stage, percent: seen.append((stage, percent)), lambda line: None,
                             lambda: bool(seen))
    assert seen and seen[0][0].startswith("horizon")
    assert code == 130, messages
    assert not out.exists() and not list(tmp_path.iterdir())  # no partial or temporary file


def test_progress_line_format():
    assert cli.parse_progress("sun: 40 % after 1.2 s, ~2.0 s left") == ("sun", 40)
    assert cli.parse_progress("horizon (sweep): 100 % after 0.5 s") == ("horizon (sweep)", 100)
    assert cli.parse_progress("wrote sun.tif (band 1 sun_visibility, band 2 sun_irradiance)") is None


# ---- qgis_process -----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def dem(tmp_path_factory):
    """A copy of the sample: QGIS writes statistics beside a raster layer it opens
    (DEM.aux.xml), which must not land in samples/."""
    return shutil.copy(SAMPLE, tmp_path_factory.mktemp("dem"))


@pytest.fixture(scope="module")
def qgis(tmp_path_factory):
    """Runs qgis_process with the provider installed by qgis/install.sh into a temporary
    profile: qgis(*args) -> CompletedProcess."""
    program = qgis_process_program()
    if program is None:
        pytest.skip("qgis_process not found: install the Debian packages qgis and python3-qgis "
                    "(scripts/install-deps.sh does)")
    executable = demlight_executable()
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen",
               QGIS_CUSTOM_CONFIG_PATH=str(tmp_path_factory.mktemp("qgis_config")))
    env.pop(cli.EXECUTABLE_ENV, None)  # the provider must find the CLI the way install.sh recorded it
    subprocess.run([os.path.join(REPO, "qgis", "install.sh"), "--executable", executable], env=env, check=True,
                   capture_output=True)

    def run(*args):
        return subprocess.run([program, *args], env=env, capture_output=True, text=True, timeout=600)
    return run


def test_qgis_process_lists_the_raster_commands(qgis):
    listing = qgis("list").stdout
    listed = {line.split("\t")[1].split(":", 1)[1] for line in listing.splitlines()
              if line.startswith("\tdemlight:")}
    # The commands that write rasters, pictures or folders; not info and sunpos, which print.
    assert listed == {"horizon", "sun", "sky", "aperture", "light", "irradiance", "insolation", "render",
                      "view", "timelapse", "sunhours", "sequence", "quicklook"}


def test_qgis_process_help_is_written_for_qgis(qgis):
    """The algorithm's help comes from the declaration: each parameter by its label with its help,
    no command-line syntax, no <pre>; qgis_process lists the parameters by name."""
    import re
    text = qgis("help", "demlight:sun").stdout
    assert "<pre>" not in text and "<p>" not in text and not re.search(r"--[a-z]", text), text
    for label in ("Time zone: IANA time zone", "Max distance (m): Horizon search distance", "Quality (auto, full)",
                  "Sun model (horizon, aperture, aperture-smooth)"):
        assert label in text, label
    for parameter in ("INPUT", "OUTPUT", "TIME", "TZ", "QUALITY", "SUN_DIAMETER", "OF", "CO"):
        assert f"\n{parameter}:" in text, parameter


def test_qgis_process_errors_name_parameters_by_their_labels(qgis, dem, tmp_path):
    # QGIS refuses what its form can check itself (the range of a number) ...
    done = qgis("run", "demlight:sun", "--", f"INPUT={dem}", "TIME=2024-06-21T07:30Z", "MAX_DISTANCE=-3",
                f"OUTPUT={tmp_path / 'bad.tif'}")
    assert done.returncode != 0 and "MAX_DISTANCE" in done.stdout + done.stderr
    # ... and the CLI's messages name parameters by their labels: a value outside an open range,
    # a time without a zone, a window outside the DEM.
    for extra, expected in ((["MAX_DISTANCE=0"], '"Max distance (m)": must be > 0'),
                            ([], 'give a time zone ("Time zone", an IANA name'),
                            (["SRCWIN=0 0 5000 5000"], '"Source window (cells)" 0 0 5000 5000: the window')):
        time = "TIME=2024-06-21T07:30" if not extra else "TIME=2024-06-21T07:30Z"
        done = qgis("run", "demlight:sun", "--", f"INPUT={dem}", time, *extra, f"OUTPUT={tmp_path / 'bad.tif'}")
        assert done.returncode != 0
        errors = [l for l in (done.stdout + done.stderr).splitlines() if "demlight: error" in l]
        assert any(expected in l for l in errors), done.stdout + done.stderr
        assert not any(re.search(r"--[a-z]", l) for l in errors), errors
    assert not list(tmp_path.iterdir())


def test_qgis_process_sun_equals_the_cli(qgis, dem, tmp_path):
    (tmp_path / "with space").mkdir()
    ours = tmp_path / "with space" / "qgis_sun.tif"
    done = qgis("run", "demlight:sun", "--", f"INPUT={dem}", f"TIME={TIME}", f"TZ={TZ}", "QUALITY=full", "OF=COG",
                "SUN_DIAMETER=1.5", f"OUTPUT={ours}")
    assert done.returncode == 0, done.stdout + done.stderr
    # The command it logs is quoted for a shell: split as a shell would, it gives the arguments
    # the CLI ran with, the output path (with its space) as one of them.
    logged = [line for line in (done.stdout + done.stderr).splitlines()
              if line.startswith(shlex.quote(demlight_executable()) + " sun ")]
    assert len(logged) == 1, done.stdout + done.stderr
    args = shlex.split(logged[0])
    assert args[args.index("--output") + 1] == str(ours), logged[0]
    theirs = tmp_path / "cli_sun.tif"
    subprocess.run([demlight_executable(), "-q", "sun", dem, "-o", str(theirs), "--time", TIME, "--tz", TZ,
                    "--quality", "full", "--of", "COG", "--sun-diameter", "1.5"], check=True)
    assert checksums(str(ours)) == checksums(str(theirs))


def test_readme_qgis_example_runs_as_written(qgis, dem, tmp_path):
    """The README's qgis_process line, its relative paths in a fresh folder holding dem.tif (a copy
    of the sample), gives what the CLI gives with the same options."""
    import shlex
    readme = open(os.path.join(REPO, "README.md"), encoding="utf-8").read()
    line = next(l for l in readme.splitlines() if "qgis_process.bin run demlight:" in l)
    words = shlex.split(line)
    words = words[words.index(next(w for w in words if w.endswith("qgis_process.bin"))) + 1:]
    shutil.copy(dem, tmp_path / "dem.tif")
    args = []
    for w in words:
        key, eq, value = w.partition("=")
        args.append(f"{key}={tmp_path / value}" if key in ("INPUT", "OUTPUT") and eq else w)
    done = qgis(*args)
    assert done.returncode == 0, done.stdout + done.stderr
    params = dict(w.split("=", 1) for w in words if "=" in w)
    theirs = tmp_path / "cli.tif"
    subprocess.run([demlight_executable(), "-q", words[1].split(":")[1], str(tmp_path / "dem.tif"), "-o", str(theirs),
                    "--time", params["TIME"], "--tz", params["TZ"]], check=True)
    assert checksums(str(tmp_path / params["OUTPUT"])) == checksums(str(theirs))


def test_qgis_process_horizon_returns_both_rasters(qgis, dem, tmp_path):
    # (Not OUTPUT=TEMPORARY_OUTPUT: qgis_process removes its temporary folder when it exits.)
    done = qgis("--json", "run", "demlight:horizon", "--", f"INPUT={dem}", "AZIMUTH=10 200",
                f"OUTPUT={tmp_path / 'qgis_h.tif'}")
    assert done.returncode == 0, done.stdout + done.stderr
    results = json.loads(done.stdout)["results"]
    assert results == {"OUTPUT": str(tmp_path / "qgis_h.tif"), "TRUNCATION_MASK": str(tmp_path / "qgis_h.truncated.tif")}
    theirs = tmp_path / "cli_h.tif"
    subprocess.run([demlight_executable(), "-q", "horizon", dem, "-o", str(theirs), "--azimuth", "10",
                    "--azimuth", "200"], check=True)
    for ours, cli_path in ((results["OUTPUT"], theirs), (results["TRUNCATION_MASK"], tmp_path / "cli_h.truncated.tif")):
        a, b = checksums(ours), checksums(str(cli_path))
        # Each names its own mask file.
        assert a["metadata"].pop("DEMLIGHT_TRUNCATION_MASK") == results["TRUNCATION_MASK"]
        assert b["metadata"].pop("DEMLIGHT_TRUNCATION_MASK") == str(tmp_path / "cli_h.truncated.tif")
        assert a == b


def test_qgis_process_timelapse_writes_its_folder(qgis, dem, tmp_path):
    ours = tmp_path / "qgis_day"
    done = qgis("run", "demlight:timelapse", "--", f"INPUT={dem}", "DATE=2024-06-21", f"TZ={TZ}", "STEP=6h",
                "FORMATS=tif", f"OUTPUT={ours}")
    assert done.returncode == 0, done.stdout + done.stderr
    theirs = tmp_path / "cli_day"
    subprocess.run([demlight_executable(), "-q", "timelapse", dem, "-o", str(theirs), "--date", "2024-06-21",
                    "--tz", TZ, "--step", "6h", "--formats", "tif"], check=True)
    assert sorted(os.listdir(ours)) == sorted(os.listdir(theirs))
    frames = [f for f in os.listdir(theirs) if f.endswith(".tif")]
    assert frames
    for f in frames:
        assert checksums(str(ours / f)) == checksums(str(theirs / f)), f


def test_qgis_process_reports_the_cli_error(qgis, dem, tmp_path):
    done = qgis("run", "demlight:sun", "--", f"INPUT={dem}", "TIME=2024-06-21T07:30",
                f"OUTPUT={tmp_path / 'no_zone.tif'}")
    assert done.returncode != 0
    assert "has no zone" in done.stdout + done.stderr
    assert not list(tmp_path.iterdir())


# ---- inside QGIS: loaded layers and the plugin zip --------------------------------------------

# Runs in its own Python (QGIS initialised offscreen): runs demlight:COMMAND as the Processing
# dialog does (runAndLoadResults: outputs loaded into the project on completion) and prints each
# loaded layer's name, renderer type, band and classification range as JSON.
_LOAD_SCRIPT = r"""
import json, sys
from qgis.core import QgsApplication, QgsProject
app = QgsApplication([], False)
app.initQgis()
sys.path[:0] = [sys.argv[1], QgsApplication.pkgDataPath() + "/python/plugins"]  # ours; QGIS's processing
from processing.core.Processing import Processing
Processing.initialize()
from demlight_processing.provider import DemlightProvider
provider = DemlightProvider()  # kept: the registry does not own the Python object
QgsApplication.processingRegistry().addProvider(provider)
import processing
processing.runAndLoadResults("demlight:" + sys.argv[2], json.loads(sys.argv[3]))
layers = []
for layer in QgsProject.instance().mapLayers().values():
    r = layer.renderer()
    layers.append({"name": layer.name(), "renderer": r.type(), "band": getattr(r, "band", lambda: None)(),
                   "min": getattr(r, "classificationMin", lambda: None)(),
                   "max": getattr(r, "classificationMax", lambda: None)()})
print("LAYERS " + json.dumps(layers))
"""


def _load_in_qgis(command, parameters, tmp_path):
    if qgis_process_program() is None:
        pytest.skip("QGIS not installed: install the Debian packages qgis and python3-qgis")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_CUSTOM_CONFIG_PATH=str(tmp_path / "profile"))
    env[cli.EXECUTABLE_ENV] = demlight_executable()
    done = subprocess.run(["/usr/bin/python3", "-c", _LOAD_SCRIPT, os.path.join(REPO, "qgis"), command,
                           json.dumps(parameters)], env=env, capture_output=True, text=True, timeout=600)
    lines = [l for l in done.stdout.splitlines() if l.startswith("LAYERS ")]
    assert done.returncode == 0 and lines, done.stdout + done.stderr
    return json.loads(lines[-1][len("LAYERS "):])


@pytest.mark.parametrize("command, extra, band, value_range", [
    ("sun", {"TIME": TIME, "TZ": TZ}, 1, (0, 1)),
    ("sky", {}, 1, (0, 1)),
    ("irradiance", {"TIME": TIME, "TZ": TZ}, 4, (0, 1000)),
    ("sunhours", {"DATE": "2024-06-21", "TZ": TZ}, 1, None),
])
def test_a_run_loads_a_layer_named_after_the_command_with_its_style(command, extra, band, value_range, dem,
                                                                     tmp_path):
    out = tmp_path / f"{command}.tif"
    layers = _load_in_qgis(command, dict(extra, INPUT=dem, OUTPUT=str(out)), tmp_path)
    stem = os.path.splitext(os.path.basename(dem))[0]
    assert [l["name"] for l in layers] == [f"{command} – {stem}"]
    assert (layers[0]["renderer"], layers[0]["band"]) == ("singlebandpseudocolor", band)
    if value_range:
        assert (layers[0]["min"], layers[0]["max"]) == value_range
    else:  # the range of the values written
        info = json.loads(subprocess.run(["gdalinfo", "-json", "-mm", str(out)], capture_output=True, text=True,
                                         check=True).stdout)
        lo, hi = info["bands"][band - 1]["computedMin"], info["bands"][band - 1]["computedMax"]
        assert layers[0]["min"] == pytest.approx(lo, abs=1e-3) and layers[0]["max"] == pytest.approx(hi, abs=1e-3)


def test_every_style_draws_the_band_its_table_names():
    import xml.etree.ElementTree as ET
    pytest.importorskip("qgis.core")
    from demlight_processing.styles import BAND_STYLES, style_path
    for command, (band, value_range, _, _) in BAND_STYLES.items():
        renderer = ET.parse(style_path(command)).getroot().find(".//rasterrenderer")
        assert renderer.get("type") == "singlebandpseudocolor", command
        assert int(renderer.get("band")) == band, command
        if value_range:
            assert (float(renderer.get("classificationMin")), float(renderer.get("classificationMax"))) == value_range


def test_the_plugin_zip_installs_into_a_fresh_profile(tmp_path):
    """qgis/package.sh's zip, unpacked into a new profile's plugins folder as QGIS's Install
    from ZIP does, is a plugin QGIS's installer reads without error, and its provider lists the
    commands once enabled."""
    program = qgis_process_program()
    if program is None:
        pytest.skip("qgis_process not found: install the Debian packages qgis and python3-qgis")
    package = tmp_path / "demlight_processing.zip"
    subprocess.run([os.path.join(REPO, "qgis", "package.sh"), str(package)], check=True, capture_output=True)
    import zipfile
    with zipfile.ZipFile(package) as z:
        names = z.namelist()
        assert "demlight_processing/metadata.txt" in names and "demlight_processing/styles/sun.qml" in names
        assert not any("__pycache__" in n or n.endswith("/executable") for n in names), names
        plugins = tmp_path / "config" / "profiles" / "default" / "python" / "plugins"
        z.extractall(plugins)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_CUSTOM_CONFIG_PATH=str(tmp_path / "config"))
    env[cli.EXECUTABLE_ENV] = demlight_executable()
    check = subprocess.run(["/usr/bin/python3", "-c", r"""
import sys
from qgis.core import QgsApplication
app = QgsApplication([], False)
app.initQgis()
sys.path.insert(0, QgsApplication.pkgDataPath() + "/python")  # QGIS's own pyplugin_installer
from pyplugin_installer.installer_data import Plugins
plugin = Plugins().getInstalledPlugin("demlight_processing", sys.argv[1], False)
print("ERROR=" + repr(plugin["error"]) + " VERSION=" + plugin["version_installed"])
""", str(plugins / "demlight_processing")], env=env, capture_output=True, text=True, timeout=300)
    version = next(l.split("=", 1)[1].strip() for l in open(os.path.join(REPO, "qgis", "demlight_processing",
                                                                         "metadata.txt")) if l.startswith("version="))
    assert f"ERROR='' VERSION={version}" in check.stdout, check.stdout + check.stderr
    subprocess.run([program, "plugins", "enable", "demlight_processing"], env=env, capture_output=True, timeout=300)
    listing = subprocess.run([program, "list"], env=env, capture_output=True, text=True, timeout=300).stdout
    assert "demlight:sun" in listing, listing


# Runs in its own Python (QGIS initialised offscreen with its GUI): opens each demlight
# algorithm's Processing dialog and prints, per algorithm, the labels of its parameters as the
# dialog shows them, their tooltips, the help panel's text and which parameters are drop-downs.
_DIALOG_SCRIPT = r"""
import json, sys
from qgis.core import QgsApplication, QgsProcessingParameterEnum
app = QgsApplication([], True)
app.initQgis()
sys.path[:0] = [sys.argv[1], QgsApplication.pkgDataPath() + "/python/plugins"]
from processing.core.Processing import Processing
Processing.initialize()
from demlight_processing.provider import DemlightProvider
provider = DemlightProvider()
QgsApplication.processingRegistry().addProvider(provider)
from processing.gui.AlgorithmDialog import AlgorithmDialog
from qgis.PyQt.QtWidgets import QCheckBox, QLabel
out = {}
for alg in provider.algorithms():
    dialog = AlgorithmDialog(alg.create(), False, None)
    labels = [w.text() for kind in (QLabel, QCheckBox) for w in dialog.findChildren(kind) if w.text()]
    out[alg.name()] = {
        "names": [p.name() for p in alg.parameterDefinitions()],
        "descriptions": [p.description() for p in alg.parameterDefinitions()],
        "labels": labels,
        "tooltips": [p.help() for p in alg.parameterDefinitions()],
        "help": alg.shortHelpString(),
        "enums": [p.name() for p in alg.parameterDefinitions() if isinstance(p, QgsProcessingParameterEnum)],
    }
    dialog.close()
print("DIALOGS " + json.dumps(out))
"""


def test_every_dialog_has_short_labels_tooltips_help_without_flags_and_drop_downs(tmp_path):
    if qgis_process_program() is None:
        pytest.skip("QGIS not installed: install the Debian packages qgis and python3-qgis")
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", QGIS_CUSTOM_CONFIG_PATH=str(tmp_path / "profile"))
    env[cli.EXECUTABLE_ENV] = demlight_executable()
    done = subprocess.run(["/usr/bin/python3", "-c", _DIALOG_SCRIPT, os.path.join(REPO, "qgis")], env=env,
                          capture_output=True, text=True, timeout=600)
    lines = [l for l in done.stdout.splitlines() if l.startswith("DIALOGS ")]
    assert done.returncode == 0 and lines, done.stdout + done.stderr
    dialogs = json.loads(lines[-1][len("DIALOGS "):])
    declared = {c["name"]: c for c in cli.load_commands(demlight_executable())["commands"]}
    assert {"sun", "sky", "horizon", "timelapse", "view"} <= set(dialogs)
    for name, d in dialogs.items():
        # The form is the declaration: the parameters QGIS is offered, in order, with their labels.
        offered = [o for o in declared[name]["options"] if "qgis" in o["front_ends"]]
        assert d["descriptions"] == [o["label"] for o in offered], name
        # Each parameter's label as the dialog shows it (QGIS adds " [optional]" to optional ones).
        for label in d["descriptions"]:
            shown = [l for l in d["labels"] if l.startswith(label)]
            assert label and shown, (name, label, d["labels"])
            assert all(len(l) <= 40 for l in shown), (name, shown)
        assert all(d["tooltips"]), name
        assert not re.search(r"--[a-z]", d["help"]) and "<pre>" not in d["help"], (name, d["help"])
        # Every option with choices is a drop-down.
        choices = {o["name"] for o in declared[name]["options"] if o["choices"] and "qgis" in o["front_ends"]}
        assert len(d["enums"]) == len(choices), (name, d["enums"], choices)
    assert "MODEL" in dialogs["sun"]["enums"]  # sun's model was free text once
    # The DEM, the output and each option named as qgis_process takes them.
    assert dialogs["sun"]["names"][:6] == ["INPUT", "Z_UNIT", "Z_FACTOR", "OUTPUT", "OF", "CO"]
    assert {"TIME", "TZ", "SUN_DIAMETER", "SKY_DIRECTIONS", "MAX_DISTANCE", "QUALITY"} <= set(dialogs["sun"]["names"])
