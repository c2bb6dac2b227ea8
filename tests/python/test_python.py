"""The Python package against the command line: numpy in equals file in equals the CLI's file,
options and errors as docs/python.md says, progress, cancelling and the GIL."""

import datetime
import json
import os
import re
import subprocess
import sys
import threading
import time
import zoneinfo

import numpy as np
import pytest

from conftest import HELENS, LUXEMBOURG, REPO, ROCKY, raster_facts

import demlight

SUN_TIME = {"time": "2024-06-21T07:30", "tz": "America/Los_Angeles"}


def same_cells(a, b):
    """Equal cell for cell, NaN equal to NaN (bits of Float32 values)."""
    return a.shape == b.shape and a.dtype == b.dtype and np.array_equal(a, b, equal_nan=a.dtype.kind == "f")


def read_bands(path):
    rasterio = pytest.importorskip("rasterio", reason="reading files back needs python3-rasterio (with python3-rioxarray)")

    with rasterio.open(path) as ds:
        return {ds.descriptions[i]: ds.read(i + 1) for i in range(ds.count)}, ds.nodata


def test_package_is_this_build():
    # The set-up command puts this build on /usr/bin/python3's path (scripts/build.sh writes a
    # .pth); the command line it is compared with is this build's too.
    assert demlight.__file__.startswith(str(REPO / "build")), demlight.__file__


def test_readme_python_example_runs(tmp_path):
    # The README's Python example, as a user runs it in a fresh shell: /usr/bin/python3 with no
    # PYTHONPATH, in the repository.
    readme = (REPO / "README.md").read_text()
    block = re.search(r"```python\n(.*?)```", readme, re.S)
    assert block, "README.md has no ```python example"
    code = block.group(1).replace("x.tif", str(tmp_path / "x.tif"))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    out = subprocess.run(["/usr/bin/python3", "-c", code], cwd=REPO, env=env, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "sun_visibility" in out.stdout
    assert (tmp_path / "x.tif").exists()


def test_sun_file_in_equals_cli(tmp_path, cli):
    r = demlight.sun(demlight.open(str(HELENS)), **SUN_TIME)
    assert list(r.bands) == ["sun_visibility", "sun_irradiance"]
    r.write(tmp_path / "py.tif")
    cli("sun", HELENS, "-o", tmp_path / "cli.tif", "--time", SUN_TIME["time"], "--tz", SUN_TIME["tz"])
    assert raster_facts(tmp_path / "py.tif") == raster_facts(tmp_path / "cli.tif")
    # The numpy bands are the file's cells (NaN where the file holds its nodata value).
    cells, nodata = read_bands(tmp_path / "cli.tif")
    for name, values in r.bands.items():
        assert same_cells(np.where(cells[name] == nodata, np.float32(np.nan), cells[name]), values), name


def test_numpy_in_equals_file_in():
    dem = demlight.open(str(HELENS))
    from_file = demlight.sun(dem, **SUN_TIME)
    from_array = demlight.sun(dem.heights, transform=dem.transform, crs=dem.crs, nodata=dem.nodata, **SUN_TIME)
    for name, values in from_file.bands.items():
        assert same_cells(values, from_array.bands[name]), name
    meta_file, meta_array = from_file.metadata, from_array.metadata
    assert meta_file.pop("DEMLIGHT_INPUT") == str(HELENS)
    assert meta_array.pop("DEMLIGHT_INPUT") == "<array>"
    assert meta_file == meta_array
    assert from_array.transform == dem.transform and from_array.nodata == from_file.nodata


def test_dem_object():
    dem = demlight.open(str(LUXEMBOURG))
    assert (dem.width, dem.height) == (95, 90)
    heights = dem.heights
    assert heights.shape == (90, 95) and heights.dtype == np.float32 and not heights.flags.writeable
    info = dem.info()
    assert info["width"] == 95 and info["height"] == 90 and info["path"] == str(LUXEMBOURG)
    assert info["elevation_max_m"] == pytest.approx(float(np.nanmax(heights)))
    assert "PROJCRS" in dem.crs or "GEOGCRS" in dem.crs
    assert len(dem.transform) == 6 and dem.transform[5] < 0


def test_every_command_equals_cli(tmp_path, cli):
    runs = {
        "horizon": (LUXEMBOURG, {"directions": 4}),
        "sky": (ROCKY, {}),
        "aperture": (LUXEMBOURG, {"sky_directions": 8}),
        "light": (LUXEMBOURG, {"time": datetime.datetime(2024, 6, 21, 9, 30, tzinfo=datetime.timezone.utc)}),
        "irradiance": (LUXEMBOURG, {"time": "2024-06-21T11:30:00+02:00", "linke": "3.5"}),
        "insolation": (LUXEMBOURG, {"date": datetime.date(2024, 6, 21), "tz": "Europe/Luxembourg", "step": "30m"}),
        "sunhours": (LUXEMBOURG, {"date": "2024-06-21", "tz": "Europe/Luxembourg",
                                  "step": datetime.timedelta(minutes=30)}),
    }
    assert set(runs) | {"sun"} == set(demlight.COMMANDS)
    flags = {
        "horizon": ["--directions", "4"],
        "sky": [],
        "aperture": ["--sky-directions", "8"],
        "light": ["--time", "2024-06-21T09:30:00Z"],
        "irradiance": ["--time", "2024-06-21T11:30:00+02:00", "--linke", "3.5"],
        "insolation": ["--date", "2024-06-21", "--tz", "Europe/Luxembourg", "--step", "30m"],
        "sunhours": ["--date", "2024-06-21", "--tz", "Europe/Luxembourg", "--step", "30m"],
    }
    for command, (path, options) in runs.items():
        written = getattr(demlight, command)(str(path), **options).write(tmp_path / (command + "_py.tif"))
        cli(command, path, "-o", tmp_path / (command + "_cli.tif"), *flags[command])
        for py_path in written:
            cli_path = py_path.replace("_py.", "_cli.")
            py_facts, cli_facts = raster_facts(py_path), raster_facts(cli_path)
            if command == "horizon":  # names its mask file, which is another path
                for facts in (py_facts, cli_facts):
                    assert facts["metadata"].pop("DEMLIGHT_TRUNCATION_MASK").endswith(".truncated.tif")
            assert py_facts == cli_facts, command


def test_options_change_results_as_on_the_command_line(tmp_path, cli):
    # A non-default search distance, quality and a window: the keyword names are the flags'.
    r = demlight.sky(str(ROCKY), max_distance=2000.0, quality="full", srcwin=(10, 20, 100, 120))
    r.write(tmp_path / "py.tif")
    cli("sky", ROCKY, "-o", tmp_path / "cli.tif", "--max-distance", "2000", "--quality", "full",
        "--srcwin", "10", "20", "100", "120")
    assert raster_facts(tmp_path / "py.tif") == raster_facts(tmp_path / "cli.tif")
    assert next(iter(r.bands.values())).shape == (120, 100)
    default = demlight.sky(str(ROCKY))
    assert r.metadata["DEMLIGHT_MAX_DISTANCE_M"] == "2000" != default.metadata["DEMLIGHT_MAX_DISTANCE_M"]


def test_tiles_equal_one_piece():
    one = demlight.sun(str(HELENS), **SUN_TIME)
    tiled = demlight.sun(str(HELENS), tile_size=100, **SUN_TIME)
    for name in one.bands:
        assert same_cells(one.bands[name], tiled.bands[name]), name


def test_aware_datetime_equals_string_with_zone():
    when = datetime.datetime(2024, 6, 21, 7, 30, tzinfo=zoneinfo.ZoneInfo("America/Los_Angeles"))
    a = demlight.sun(str(LUXEMBOURG), time=when)
    b = demlight.sun(str(LUXEMBOURG), time="2024-06-21T07:30:00-07:00")
    assert a.metadata == b.metadata
    assert same_cells(a.bands["sun_visibility"], b.bands["sun_visibility"])


def test_signature_and_help_name_every_cli_option(cli):
    # Every long option of `demlight sun --help` is a keyword of demlight.sun (but the output's
    # and -v), described in help(demlight.sun), with the default the command line shows.
    import inspect

    text = cli("sun", "--help").stdout
    # "  --pressure FLOAT:[0, 5000]=1013.25": the flag, its type and check, "=" and its default.
    options = re.findall(r"^\s+(?:-\w,)?--([a-z][a-z-]*)(.*)$", text, re.M)
    params = inspect.signature(demlight.sun).parameters
    doc = demlight.sun.__doc__
    checked = 0
    for flag, rest in options:
        if flag in ("help", "output", "of", "co", "verbose"):
            continue
        keyword = flag.replace("-", "_")
        assert keyword in params and keyword in doc, keyword
        default_shown = re.search(r"(?<=\S)=(\S+)", rest)
        if default_shown:
            shown = default_shown.group(1)
            default = params[keyword].default
            assert (float(shown) == default) if isinstance(default, (int, float)) else shown == default, keyword
            checked += 1
    assert checked >= 8  # sun_diameter, pressure, temperature, model, refraction, threads, quality, ...
    assert "Angular diameter of the sun disk (degrees)" in doc


@pytest.mark.parametrize("call, words", [
    (lambda: demlight.sun(str(HELENS), time="2024-06-21T07:30"), ["tz"]),
    (lambda: demlight.sun(str(HELENS), time="2024-06-21T07:30", tz="Mars/Olympus"), ["Mars/Olympus"]),
    (lambda: demlight.sky(str(HELENS), max_distance=-5.0), ["max_distance"]),
    (lambda: demlight.sky(str(HELENS), quality="best"), ["quality", "best"]),
    (lambda: demlight.irradiance(str(HELENS), time="2024-06-21T12:00:00Z", linke="20"), ["linke", "20"]),
    (lambda: demlight.horizon(str(HELENS)), ["azimuth", "directions"]),
    (lambda: demlight.sky(str(HELENS), srcwin=(0, 0, 5000, 10)), ["srcwin", "327 x 468"]),
    (lambda: demlight.sky(str(HELENS), tile_size="x"), ["tile_size", "'x'"]),
    (lambda: demlight.sunhours(str(HELENS), date="2024-06-21"), ["tz"]),
    (lambda: demlight.sky(str(HELENS), albedo_raster="no/such/albedo.tif"), ["albedo_raster", "no such file"]),
    (lambda: demlight.sky("no/such/dem.tif"), ["no/such/dem.tif", "no such file"]),
    (lambda: demlight.sky(np.zeros((10, 10), np.float32)), ["transform"]),
    (lambda: demlight.sky(np.zeros((10, 10), np.float32), transform=(0, 30, 0, 0, 0, -30), crs=""),
     ["<array>", "coordinate reference system"]),
    (lambda: demlight.sky(demlight.open(str(HELENS)), z_unit="ft"), ["z_unit", "demlight.open"]),
    # An unreadable CRS was reported as a missing one.
    (lambda: demlight.sky(np.zeros((10, 10), np.float32), transform=(0, 30, 0, 0, 0, -30), crs="EPSG:999999"),
     ["CRS 'EPSG:999999' is not one GDAL reads"]),
    # The library's DEM-opening messages named its C++ fields (HeightOptions::zUnit).
    (lambda: demlight.sun(str(HELENS), time="2024-06-21T16:00Z", z_unit="furlong"), ["z_unit \"furlong\""]),
    (lambda: demlight.open(str(HELENS), z_factor=-2), ["z_factor -2"]),
    (lambda: demlight.open(str(HELENS), z_unit="ft", z_factor=2), ["z_unit \"ft\" and z_factor 2"]),
])
def test_errors_name_keywords(call, words):
    with pytest.raises(demlight.Error) as e:
        call()
    message = str(e.value)
    for word in words:
        assert word in message, message
    assert "--" not in message, message
    assert "::" not in message, message


def test_write_takes_one_creation_option_as_a_string(tmp_path):
    # A string had been split into its characters (a garbled GDAL error).
    r = demlight.sun(str(HELENS), **SUN_TIME)
    r.write(str(tmp_path / "one.tif"), creation_options="COMPRESS=DEFLATE")
    r.write(str(tmp_path / "list.tif"), creation_options=["COMPRESS=DEFLATE"])
    assert raster_facts(tmp_path / "one.tif") == raster_facts(tmp_path / "list.tif")
    info = subprocess.run(["gdalinfo", str(tmp_path / "one.tif")], check=True, capture_output=True, text=True).stdout
    assert "COMPRESSION=DEFLATE" in info


def test_an_array_crs_may_be_an_epsg_code_or_a_crs_object():
    heights = np.full((12, 10), 100.0, np.float32)
    transform = (500000, 30, 0, 4000000, 0, -30)
    wkt = demlight.from_array(heights, transform, "EPSG:26710").crs
    assert "NAD27 / UTM zone 10N" in wkt
    assert demlight.from_array(heights, transform, 26710).crs == wkt
    pyproj = pytest.importorskip("pyproj")
    assert demlight.from_array(heights, transform, pyproj.CRS.from_epsg(26710)).crs == wkt


def test_write_refuses_to_overwrite_the_input(tmp_path):
    dem_path = tmp_path / "dem.tif"
    dem_path.write_bytes(LUXEMBOURG.read_bytes())
    r = demlight.sky(str(dem_path))
    with pytest.raises(demlight.Error, match="overwrite its input"):
        r.write(dem_path)


def test_progress_reports_and_cancels():
    seen = []
    demlight.sky(str(ROCKY), progress=lambda f, stage: seen.append((f, stage)))
    assert seen and all(0 <= f <= 1 for f, _ in seen)
    with pytest.raises(demlight.Cancelled):
        demlight.sky(str(ROCKY), progress=lambda f, stage: False)


def test_exception_in_progress_propagates():
    class Stop(Exception):
        pass

    def progress(fraction, stage):
        raise Stop(stage)

    with pytest.raises(Stop):
        demlight.sky(str(ROCKY), progress=progress)


def test_keyboard_interrupt_stops_the_work():
    # Ctrl-C (SIGINT's handler raises KeyboardInterrupt) stops the work midway, not after it.
    import _thread

    seen = []
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        demlight.sky(str(HELENS), quality="full", sky_directions=512, progress=lambda f, stage: seen.append(f))
    timer.join()
    assert seen and max(seen) < 0.9, "the work ran to %.2f" % max(seen)


def test_gil_released_while_computing():
    # Another Python thread keeps running while demlight computes; were the GIL held, it would
    # stall for the whole computation.
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    worker = threading.Thread(target=count)
    worker.start()
    start = time.monotonic()
    demlight.sky(str(HELENS), quality="full", sky_directions=64)
    end = time.monotonic()
    done.set()
    worker.join()
    during = [t for t in ticks if start < t < end]
    gaps = np.diff([start] + during + [end])
    assert end - start > 0.2, "the computation was too short to tell"
    assert gaps.max() < (end - start) / 2, "the other thread stalled %.3f s of %.3f s" % (gaps.max(), end - start)


def test_to_xarray_carries_crs_and_transform():
    pytest.importorskip("rioxarray", reason="rioxarray (python3-rioxarray) attaches the CRS")
    r = demlight.sun(str(HELENS), **SUN_TIME)
    ds = r.to_xarray()
    assert set(ds.data_vars) == set(r.bands)
    assert tuple(ds.rio.transform().to_gdal()) == tuple(r.transform)
    assert ds.rio.crs is not None and ds.rio.crs.to_wkt()
    assert same_cells(ds["sun_visibility"].values, r.bands["sun_visibility"])
    assert ds.sizes["x"] == 327 and ds.sizes["y"] == 468


def test_to_xarray_nodata_is_the_encoding_of_its_nan_cells(tmp_path):
    # The cells hold NaN where the command's file holds -32767: the nodata value is the encoding,
    # so a file saved with rioxarray masks the same cells as the command's file.
    pytest.importorskip("rioxarray", reason="rioxarray (python3-rioxarray) attaches the nodata")
    import rasterio  # rioxarray's reader (osgeo's bindings beside it in one process crash at exit)
    r = demlight.sun(str(HELENS), **SUN_TIME)
    da = r.to_xarray()["sun_visibility"]
    voids = np.isnan(r.bands["sun_visibility"])
    assert voids.sum() > 0
    assert np.isnan(da.rio.nodata) and da.rio.encoded_nodata == -32767.0
    da.rio.to_raster(tmp_path / "xr.tif")
    r.write(str(tmp_path / "cli.tif"))
    for name in ("xr.tif", "cli.tif"):
        with rasterio.open(tmp_path / name) as f:
            assert np.array_equal(f.read_masks(1) == 0, voids), name


# ---- Keywords, formats and messages ------------------------------------------------------------

@pytest.mark.parametrize("call, words", [
    (lambda: demlight.sky(str(HELENS), max_dist=5000.0), ["max_dist", "did you mean max_distance?"]),
    (lambda: demlight.sun(str(HELENS), tiem="2024-06-21T07:30"), ["tiem", "did you mean time?"]),
    (lambda: demlight.sky(str(HELENS), bogus=1), ["bogus", "max_distance"]),
    (lambda: demlight.sunpos("2024-06-21T12:00Z", lat=46, lon=7, elevaton=500), ["did you mean elevation?"]),
])
def test_unknown_keywords_raise_type_error_with_the_nearest_name(call, words):
    # A misspelt keyword raised demlight.Error, as a bad value does; Python raises TypeError.
    with pytest.raises(TypeError) as e:
        call()
    for word in words:
        assert word in str(e.value), str(e.value)


def test_format_names_in_any_case(tmp_path):
    r = demlight.sun(str(HELENS), srcwin=(0, 0, 100, 80), **SUN_TIME)
    r.write(tmp_path / "upper.tif", format="COG")
    r.write(tmp_path / "lower.tif", format="cog")  # refused before
    assert raster_facts(tmp_path / "upper.tif") == raster_facts(tmp_path / "lower.tif")
    info = subprocess.run(["gdalinfo", str(tmp_path / "lower.tif")], check=True, capture_output=True, text=True).stdout
    assert "LAYOUT=COG" in info
    with pytest.raises(demlight.Error) as e:
        r.write(tmp_path / "bad.tif", format="png")
    assert "--" not in str(e.value), str(e.value)


def test_write_messages_name_keywords_not_flags(tmp_path):
    dem_path = tmp_path / "dem.tif"
    dem_path.write_bytes(LUXEMBOURG.read_bytes())
    r = demlight.sky(str(dem_path), srcwin=(0, 0, 40, 30))
    with pytest.raises(demlight.Error) as e:
        r.write(dem_path)
    message = str(e.value)
    assert "choose another path" in message, message  # "choose another -o" before
    assert not re.search(r"(^|\s)-o\b", message), message


def test_sunpos_is_the_commands(cli):
    import json

    got = demlight.sunpos("2024-06-21T12:00", lat=46.5, lon=7.5, tz="Europe/Zurich", elevation=500)
    printed = json.loads(cli("sunpos", "--time", "2024-06-21T12:00", "--lat", "46.5", "--lon", "7.5",
                             "--tz", "Europe/Zurich", "--elevation", "500", "--json").stdout)
    assert got == printed
    assert 60 < got["elevation_deg"] < 61 and got["sunrise"].startswith("2024-06-21T05:3")
    aware = datetime.datetime(2024, 6, 21, 10, tzinfo=datetime.timezone.utc)
    assert demlight.sunpos(aware, 46.5, 7.5)["azimuth_deg"] == got["azimuth_deg"]
    with pytest.raises(demlight.Error) as e:
        demlight.sunpos("2024-06-21T12:00Z", lat=91, lon=7)
    assert "lat" in str(e.value) and "--" not in str(e.value)
    assert "elevation_deg" in demlight.sunpos.__doc__ and "lat, required" in demlight.sunpos.__doc__


def test_docstrings_list_each_band_with_its_unit():
    # The table help() shows is what each command computes under its default options.
    runs = {"horizon": {"directions": 2}, "sun": dict(SUN_TIME), "sky": {}, "aperture": {}, "light": dict(SUN_TIME),
            "irradiance": {"time": "2024-06-21T12:00:00-07:00"},
            "insolation": {"date": "2024-06-21", "tz": "America/Los_Angeles", "step": "2h"},
            "sunhours": {"date": "2024-06-21", "tz": "America/Los_Angeles", "step": "2h"}}
    assert set(runs) == set(demlight.COMMANDS) == set(demlight.BANDS)
    for command, options in runs.items():
        r = getattr(demlight, command)(str(HELENS), srcwin=(100, 100, 24, 20), **options)
        listed, _ = demlight.BANDS[command]
        if command == "horizon":  # one band of each kind per azimuth
            listed = [(n.replace("<deg>", az), u) for n, u in listed for az in ("0", "180")]
            listed.sort(key=lambda b: not b[0].startswith("horizon"))
        listed = [(n, u.replace("<tz>", options.get("tz", ""))) for n, u in listed]
        assert list(r.units.items()) == listed, command
        doc = getattr(demlight, command).__doc__
        for name, unit in demlight.BANDS[command][0]:
            assert name in doc, (command, name)


# ---- rasterio and xarray -----------------------------------------------------------------------

def test_a_rasterio_affine_is_a_transform():
    affine = pytest.importorskip("affine")
    dem = demlight.open(str(HELENS))
    # Affine has 9 numbers in its own order; GDAL's 6 were required ("got 9").
    a = demlight.sun(dem.heights, transform=affine.Affine.from_gdal(*dem.transform), crs=dem.crs, nodata=dem.nodata,
                     **SUN_TIME)
    b = demlight.sun(dem.heights, transform=dem.transform, crs=dem.crs, nodata=dem.nodata, **SUN_TIME)
    assert a.transform == b.transform == dem.transform
    assert same_cells(a.bands["sun_visibility"], b.bands["sun_visibility"])


@pytest.mark.parametrize("path, masked", [(HELENS, False), (HELENS, True), (LUXEMBOURG, False)])
def test_a_data_array_in_gives_the_file_bytes(tmp_path, cli, path, masked):
    # Float32 with nodata -32767, the same read as NaN (masked), and Int16 with nodata -32768.
    rioxarray = pytest.importorskip("rioxarray")
    da = rioxarray.open_rasterio(path, masked=masked)
    r = demlight.sun(da, **SUN_TIME)
    r.write(tmp_path / "da.tif")
    cli("sun", path, "-o", tmp_path / "cli.tif", "--time", SUN_TIME["time"], "--tz", SUN_TIME["tz"])
    assert raster_facts(tmp_path / "da.tif") == raster_facts(tmp_path / "cli.tif")
    assert r.metadata["DEMLIGHT_INPUT"] == str(path)  # the file the DataArray was read from
    dem = demlight.from_array(da)
    assert dem.transform == demlight.open(str(path)).transform


def test_a_data_array_without_a_crs_is_an_error():
    xr = pytest.importorskip("xarray")
    pytest.importorskip("rioxarray")
    da = xr.DataArray(np.zeros((10, 10), np.float32), dims=("y", "x"),
                      coords={"y": 4000000 - 30 * (np.arange(10) + 0.5), "x": 500000 + 30 * (np.arange(10) + 0.5)})
    with pytest.raises(demlight.Error, match="without a CRS"):
        demlight.sky(da)
    r = demlight.sky(da, crs="EPSG:32610")
    assert r.transform == (500000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0)


def test_to_xarray_rio_to_raster_round_trips_every_product(tmp_path):
    # horizon's uint8 masks carried a fill value rioxarray read as NaN ("cannot convert float NaN
    # to integer"), and one nodata for the file's bands must fit both rasters.
    pytest.importorskip("rioxarray")
    import rasterio

    runs = {"horizon": {"directions": 4}, "sun": dict(SUN_TIME), "sky": {}, "aperture": {},
            "light": dict(SUN_TIME), "irradiance": {"time": "2024-06-21T12:00:00-07:00"},
            "insolation": {"date": "2024-06-21", "tz": "America/Los_Angeles", "step": "2h"},
            "sunhours": {"date": "2024-06-21", "tz": "America/Los_Angeles", "step": "2h"}}
    assert set(runs) == set(demlight.COMMANDS)
    for command, options in runs.items():
        r = getattr(demlight, command)(str(HELENS), srcwin=(0, 0, 60, 50), **options)
        ds = r.to_xarray()
        ds.rio.to_raster(tmp_path / (command + ".tif"))
        with rasterio.open(tmp_path / (command + ".tif")) as f:
            assert list(f.descriptions) == list(r.bands), command
            for i, (name, values) in enumerate(r.bands.items()):
                cells = f.read(i + 1, masked=True).filled(np.nan)
                if values.dtype.kind != "f":  # a mask: 0 and 1, NaN at its nodata
                    values = np.where(values == r.rasters[1].nodata, np.nan, values).astype(np.float32)
                assert same_cells(cells, values), (command, name)
            assert f.transform.to_gdal() == r.transform
        for name in ds.data_vars:  # one band alone too
            ds[name].rio.to_raster(tmp_path / "one.tif")

def south_east_tower():
    """Flat ground at 0 m on UTM 10N's central meridian (true north = grid north), 10 m cells, a
    100 m tower of 3 x 3 cells due south-east of cell (50, 50); the observer is that cell's centre."""
    heights = np.zeros((101, 101), dtype=np.float32)
    heights[70:73, 70:73] = 100
    transform = (500000 - 505.0, 10, 0, 4982950 + 505.0, 0, -10)
    return heights, transform, (500000.0, 4982950.0)


def test_horizon_profile_conventions_and_the_cli(tmp_path, cli):
    heights, transform, observer = south_east_tower()
    dem = demlight.from_array(heights, transform, "EPSG:32610")
    az, el = demlight.horizon_profile(dem, at_xy=observer)
    assert az.dtype == np.float64 and el.dtype == np.float64 and az.shape == el.shape == (48,)
    np.testing.assert_array_equal(az, np.arange(48) * 7.5)
    assert az[np.argmax(el)] == 135.0  # the tower, due south-east, north-based clockwise
    assert el.max() > 15 and np.abs(np.delete(el, 18)).max() < 0.05
    south, el_south = demlight.horizon_profile(dem, at_xy=observer, azimuth_origin="south")
    assert south[np.argmax(el_south)] == -45.0  # PVGIS: 0 = south, east negative
    assert south[0] == -180.0 and south[24] == 0.0 and south[36] == 90.0
    np.testing.assert_array_equal(el, el_south)

    # The same heights as a file for the command line: an ASCII grid, then a GeoTIFF with the CRS.
    grid = tmp_path / "tower.asc"
    with open(grid, "w") as f:
        f.write("ncols 101\nnrows 101\nxllcorner %r\nyllcorner %r\ncellsize 10\n"
                % (transform[0], transform[3] - 1010))
        for row in heights:
            f.write(" ".join("%g" % v for v in row) + "\n")
    path = tmp_path / "tower.tif"
    subprocess.run(["gdal_translate", "-q", "-a_srs", "EPSG:32610", "-ot", "Float32", str(grid), str(path)],
                   check=True, capture_output=True)
    printed = cli("horizon", path, "--at-xy", "%r,%r" % observer, "--point-format", "json").stdout
    profile = json.loads(printed)["horizon"]
    np.testing.assert_allclose(el, [p["elevation_deg"] for p in profile], atol=0)
    eight = demlight.horizon_profile(str(path), at_xy=observer, directions=8)
    np.testing.assert_array_equal(eight[0], np.arange(8) * 45.0)


def test_horizon_profile_refuses_bad_arguments():
    heights, transform, observer = south_east_tower()
    dem = demlight.from_array(heights, transform, "EPSG:32610")
    for kwargs in ({}, {"at": (45, -123), "at_xy": observer}, {"at_xy": observer, "azimuth_origin": "east"},
                   {"at_xy": observer, "directions": 0}):
        with pytest.raises(demlight.Error):
            demlight.horizon_profile(dem, **kwargs)


def test_signatures_and_docstrings_are_the_declarations(cli):
    # The Python signatures are made from the same declarations as the command line's options:
    # every option `demlight options --json` offers to Python is a keyword of the function, in
    # its order, with its default; its help (naming keywords, never flags) is in the docstring.
    import inspect

    declared = {c["name"]: c for c in json.loads(cli("options", "--json").stdout)["commands"]}
    assert set(demlight.COMMANDS) <= set(declared)
    for command in list(demlight.COMMANDS) + ["sunpos"]:
        options = [o for o in declared[command]["options"] if "python" in o["front_ends"]]
        signature = inspect.signature(getattr(demlight, command)).parameters
        keywords = [name for name in signature if name not in ("dem", "transform", "crs", "nodata", "progress")]
        assert sorted(keywords) == sorted(o["keyword"] for o in options), command
        doc = getattr(demlight, command).__doc__
        for o in options:
            assert o["python_help"].split()[0] in doc, (command, o["keyword"])
            assert "--" not in o["python_help"], (command, o["keyword"], o["python_help"])
            default = signature[o["keyword"]].default
            if o["default"] is not None and o["type"] in ("FLOAT", "INT") and o["max_values"] == 1:
                assert default == float(o["default"]), (command, o["keyword"])
        # The command line's own options (-o, -v, --of, --co, --at) are not keywords.
        flags_only = [o["name"] for o in declared[command]["options"] if "python" not in o["front_ends"]]
        assert not set(flags_only) & set(keywords), command


def test_every_bad_value_is_refused_naming_its_keyword():
    # Each keyword with a range or choices, given a value outside them: demlight.Error naming the
    # keyword, never a flag, before any work.
    checked = 0
    for command in demlight.COMMANDS:
        for o in demlight._command_options(command):
            if not o["range"] and not o["choices"]:
                continue
            value = "no-such-choice" if o["choices"] else -1e12
            if o["max_values"] != 1:
                value = [value] * max(o["min_values"], 1)
            with pytest.raises(demlight.Error) as e:
                getattr(demlight, command)(str(ROCKY), **{o["keyword"]: value})
            message = str(e.value)
            assert message.startswith(o["keyword"]) and "--" not in message, (command, message)
            checked += 1
    assert checked > 60
