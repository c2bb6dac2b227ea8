"""demlight.dask on a LocalCluster of 2 worker processes: a real DEM in windows, each a task that
reads its own halo, written into one file that is the command line's, bit for bit."""

import re

import pytest

from conftest import HELENS, LUXEMBOURG, REPO, ROCKY, raster_facts

distributed = pytest.importorskip("distributed", reason="demlight.dask needs python3-distributed (scripts/install-deps.sh)")
import demlight  # noqa: E402
import demlight.dask  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_windows_cover_the_extent_once():
    extent = (3, 5, 330, 473)
    for chunks in (100, (64, 200)):
        ws = demlight.dask.windows(extent, chunks)
        cells = sum((c1 - c0) * (r1 - r0) for c0, r0, c1, r1 in ws)
        assert cells == (330 - 3) * (473 - 5)
        assert all(extent[0] <= c0 < c1 <= extent[2] and extent[1] <= r0 < r1 <= extent[3] for c0, r0, c1, r1 in ws)


def test_chunks_are_whole_numbers_of_cells_or_an_error():
    import numpy as np
    extent = (0, 0, 327, 300)
    assert demlight.dask.windows(extent, np.int64(100)) == demlight.dask.windows(extent, 100)
    assert demlight.dask.windows(extent, (np.int32(100), 50)) == demlight.dask.windows(extent, (100, 50))
    # 0 had become 1: 98 100 one-cell tasks; True the same; -5 and floats failed inside the binding.
    for bad in (0, True, -5, 100.0, "100", (0, 5), (100, 50.5), (1, 2, 3)):
        with pytest.raises(demlight.Error, match="chunks: expected a whole number of cells"):
            demlight.dask.windows(extent, bad)


def test_sun_in_windows_equals_cli(tmp_path, client, cli):
    # 327 x 468 cells in windows of 128: 3 x 4 = 12 tasks on the two workers. The paths as
    # pathlib.Path, as demlight.open takes them (the workers' tasks had failed on them).
    out = demlight.dask.run("sun", HELENS, tmp_path / "dask.tif", chunks=128, client=client,
                            time="2024-06-21T07:30", tz="America/Los_Angeles")
    assert out == [str(tmp_path / "dask.tif")]
    assert len(demlight.dask.windows((0, 0, 327, 468), 128)) >= 4
    cli("sun", HELENS, "-o", tmp_path / "cli.tif", "--time", "2024-06-21T07:30", "--tz", "America/Los_Angeles")
    assert raster_facts(tmp_path / "dask.tif") == raster_facts(tmp_path / "cli.tif")


def test_dask_arrays_equal_cli(tmp_path, client, cli):
    import numpy as np

    rasterio = pytest.importorskip("rasterio", reason="reading files back needs python3-rasterio (with python3-rioxarray)")

    arrays = demlight.dask.run("sun", str(HELENS), None, chunks=(200, 150), client=client,
                               time="2024-06-21T07:30", tz="America/Los_Angeles")
    assert list(arrays) == ["sun_visibility", "sun_irradiance"]
    assert arrays["sun_visibility"].chunks == ((200, 200, 68), (150, 150, 27))
    cli("sun", HELENS, "-o", tmp_path / "cli.tif", "--time", "2024-06-21T07:30", "--tz", "America/Los_Angeles")
    with rasterio.open(tmp_path / "cli.tif") as ds:
        for i, name in enumerate(ds.descriptions):
            cells = ds.read(i + 1)
            expected = np.where(cells == ds.nodata, np.float32(np.nan), cells)
            assert np.array_equal(arrays[name].compute(), expected, equal_nan=True), name


def test_horizon_cog_window_in_row_strips_equals_cli(tmp_path, client, cli):
    # Two output files (horizons, truncation mask), COG, a source window, in windows of 32 rows
    # x 60 columns.
    out = demlight.dask.run("horizon", str(LUXEMBOURG), str(tmp_path / "dask.tif"), chunks=(32, 60), client=client,
                            format="COG", azimuth=[45.0, 200.0], max_distance=3000.0, srcwin=(5, 3, 85, 80))
    assert len(out) == 2
    cli("horizon", LUXEMBOURG, "-o", tmp_path / "cli.tif", "--of", "COG", "--azimuth", "45", "200",
        "--max-distance", "3000", "--srcwin", "5", "3", "85", "80")
    for path in out:
        dask_facts = raster_facts(path)
        cli_facts = raster_facts(path.replace("dask.", "cli."))
        for facts in (dask_facts, cli_facts):
            facts["metadata"].pop("DEMLIGHT_TRUNCATION_MASK")
        assert dask_facts == cli_facts


def test_a_replaced_dem_is_read_again(tmp_path, client, cli):
    # Workers keep a DEM open between runs; a file replaced at the same path is opened again.
    dem = tmp_path / "dem.tif"
    dem.write_bytes(LUXEMBOURG.read_bytes())
    demlight.dask.run("sky", str(dem), str(tmp_path / "first.tif"), chunks=48, client=client)
    dem.write_bytes(ROCKY.read_bytes())
    demlight.dask.run("sky", str(dem), str(tmp_path / "second.tif"), chunks=48, client=client)
    cli("sky", dem, "-o", tmp_path / "cli.tif")
    assert raster_facts(tmp_path / "second.tif") == raster_facts(tmp_path / "cli.tif")


def test_error_in_a_window_leaves_no_file(tmp_path, client):
    with pytest.raises(demlight.Error, match="tz"):
        demlight.dask.run("sun", str(HELENS), str(tmp_path / "x.tif"), chunks=128, client=client, time="2024-06-21T07:30")
    assert list(tmp_path.iterdir()) == []


def dask_examples(path):
    blocks = re.findall(r"```python\n(.*?)```", (REPO / path).read_text(), re.S)
    return [b for b in blocks if "Client(" in b]


def test_a_write_over_the_input_names_out_path(tmp_path, client):
    # The output is named as run() names it (out_path), not as Result.write (path) or the
    # command line (-o) do.
    dem = tmp_path / "dem.tif"
    dem.write_bytes(HELENS.read_bytes())
    with pytest.raises(demlight.Error) as e:
        demlight.dask.run("sky", str(dem), str(dem), chunks=128, client=client)
    message = str(e.value)
    assert "choose another out_path" in message and message.startswith("out_path "), message


def test_readme_dask_example_runs_as_a_saved_script(tmp_path, cli):
    # Saved as a script, the example hung: Client() starts worker processes that import the
    # script again, and without the __main__ guard each started a cluster of its own.
    import os
    import subprocess
    import sys

    example = dask_examples("README.md")
    assert example, "README.md has no demlight.dask example"
    code = example[0].replace("sun_dask.tif", str(tmp_path / "sun_dask.tif")).replace("samples/", str(REPO / "samples") + "/")
    code = code.replace("Client()", "Client(n_workers=2, threads_per_worker=1, dashboard_address=None)")
    script = tmp_path / "readme_dask.py"
    script.write_text(code)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = os.path.dirname(os.path.dirname(demlight.__file__))  # this package, as the tests import it
    out = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    cli("sun", HELENS, "-o", tmp_path / "cli.tif", "--time", "2024-06-21T07:30", "--tz", "America/Los_Angeles")
    facts = raster_facts(tmp_path / "sun_dask.tif")
    assert facts == raster_facts(tmp_path / "cli.tif")


@pytest.mark.parametrize("path", ["README.md", "docs/python.md"])
def test_dask_examples_guard_their_work(path):
    examples = dask_examples(path)
    assert examples, path
    for code in examples:
        guard = code.index('if __name__ == "__main__":')
        assert guard < code.index("Client("), code
