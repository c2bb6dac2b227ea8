"""Shared fixtures of the Python tests (run by scripts/test.sh; docs/testing.md).

The package under test is the one `import demlight` finds (scripts/build.sh puts this build's
python/ folder on /usr/bin/python3's path); the command line to compare with is this build's
(DEMLIGHT_CLI, default build/release/cli/demlight)."""

import hashlib
import json
import math
import os
import pathlib
import subprocess
import tempfile

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]
SAMPLES = REPO / "samples"
HELENS = SAMPLES / "mount_st_helens_1980_usgs.dem"
LUXEMBOURG = SAMPLES / "luxembourg_elev_terra.tif"
ROCKY = SAMPLES / "rocky_mountain_np_dem.tif"
CLI = pathlib.Path(os.environ.get("DEMLIGHT_CLI", REPO / "build" / "release" / "cli" / "demlight"))


@pytest.fixture(scope="session")
def cli():
    """Runs the demlight command line; returns its completed process (raises on failure)."""
    if not CLI.exists():
        pytest.skip("no demlight command line at %s: build it first (scripts/build.sh)" % CLI)

    def run(*args):
        return subprocess.run([str(CLI), "-q", *[str(a) for a in args]], check=True, capture_output=True, text=True)

    return run


def values_digest(path):
    """SHA-256 of every band's stored values (gdal_translate to raw ENVI bytes): gdalinfo's
    checksum rounds floating-point values to whole numbers, so only the bytes show two rasters
    are the same bit for bit."""
    with tempfile.TemporaryDirectory() as scratch:
        raw = os.path.join(scratch, "values.bin")
        subprocess.run(["gdal_translate", "-q", "-of", "ENVI", str(path), raw], check=True, capture_output=True)
        with open(raw, "rb") as f:
            return hashlib.sha256(f.read()).hexdigest()


def raster_facts(path):
    """What the project calls byte-identical (docs/python.md): the bands' stored bytes, every
    band's checksum, type, description, unit and nodata, the georeference, and the DEMLIGHT_*
    metadata but DEMLIGHT_COMMAND, as gdalinfo reads them."""
    info = json.loads(subprocess.run(["gdalinfo", "-json", "-checksum", str(path)], check=True,
                                     capture_output=True, text=True).stdout)
    metadata = dict(info.get("metadata", {}).get("", {}))
    metadata.pop("DEMLIGHT_COMMAND", None)

    def nodata(band):
        v = band.get("noDataValue")
        return "nan" if isinstance(v, str) or (isinstance(v, float) and math.isnan(v)) else v

    bands = [(b["checksum"], b["type"], b.get("description"), b.get("unit"), nodata(b)) for b in info["bands"]]
    return {"values": values_digest(path), "size": info["size"], "geoTransform": info["geoTransform"],
            "wkt": info["coordinateSystem"]["wkt"], "bands": bands, "metadata": metadata}
