"""demlight.dask: a raster command over a DEM larger than one worker's memory, on dask.distributed.

    from dask.distributed import Client
    import demlight.dask
    client = Client("tcp://scheduler:8786")          # or LocalCluster()
    demlight.dask.run("sun", "dem.tif", "sun.tif", chunks=2048, client=client,
                      time="2024-06-21T07:30", tz="America/Los_Angeles")

The DEM is cut into windows of `chunks` cells; each window is one task, which opens the DEM at
its path (every worker must read the same path or URL) and computes the window with the halo the
product needs read from the file: the graph of window tasks that dask.array.map_overlap would
make with depth = the product's halo, without sending the halos through the scheduler. The
client writes each window into one streamed GeoTIFF (or COG) as it arrives, with the command
line's own writer, and renames it at the end: the file is the command line's output bit for bit
(tests/python/test_dask.py). docs/python.md says more.
"""

import functools as _functools
import numbers as _numbers
import os as _os

import demlight as _demlight
from demlight import _demlight as _core

__all__ = ["run", "windows"]


def windows(extent, chunks):
    """The windows (col0, row0, col1, row1) of `chunks` cells (an int, or (rows, columns))
    covering `extent`, row by row from the north-west corner."""
    def cells(n):
        # Whole numbers of cells, numpy's included; not bool (True would be a 1-cell window).
        if isinstance(n, bool) or not isinstance(n, _numbers.Integral) or n < 1:
            raise _demlight.Error("chunks: expected a whole number of cells >= 1, or (rows, columns) of them; "
                                  "got %r" % (chunks,))
        return int(n)

    if not (isinstance(chunks, (tuple, list)) and len(chunks) == 2):
        return [tuple(w) for w in _core.tiles(list(extent), cells(chunks))]
    rows, cols = cells(chunks[0]), cells(chunks[1])
    col0, row0, col1, row1 = extent
    return [(c, r, min(c + cols, col1), min(r + rows, row1))
            for r in range(row0, row1, rows) for c in range(col0, col1, cols)]


@_functools.lru_cache(maxsize=4)
def _open(path, z_unit, z_factor, stamp):
    """One opened DEM per worker process, path and file version (`stamp`): its geometry and
    opening pass are shared by the windows the worker computes, and a file replaced between two
    runs on a long-lived cluster is opened again."""
    return _core.open(path, z_unit, z_factor, None)


def _stamp(path):
    """The file's modification time and size, or None where the OS cannot see it (/vsicurl/...)."""
    try:
        st = _os.stat(path)
    except OSError:
        return None
    return (st.st_mtime_ns, st.st_size)


def _compute(product, dem_path, arguments, window):
    """A task: one window of the command, on a worker."""
    call = _core.parse(product, arguments)
    dem = _open(dem_path, call.z_unit, call.z_factor, _stamp(dem_path))
    return call.compute_window(dem, list(window), None)


def run(product, dem_path, out_path, chunks=2048, client=None, format="GTiff", creation_options=(),  # noqa: A002
        progress=None, **options):
    """Runs the raster command `product` (a command name: "sun", "sky", ...) over the DEM at
    `dem_path` in windows of `chunks` cells (an int, or (rows, columns)) on a dask.distributed
    client (default: the current one), and writes `out_path` as `demlight <product> dem_path -o
    out_path` does (format "GTiff" or "COG" in any case, creation_options as -co). options: the keyword
    options of demlight.<product> (srcwin included; tile_size and memory_limit are not used:
    chunks sets the windows). progress: callback(fraction, stage) on the client as windows
    arrive. Returns the paths written (horizon: the horizons and the truncation mask).

    With out_path None nothing is written: returns a dict band name -> dask array (rows,
    columns), one chunk per window, computed when asked for (the first window is computed at
    once, for the bands' names and types).
    """
    if product not in _demlight.COMMANDS:
        raise _demlight.Error("product '%s': expected one of %s" % (product, ", ".join(_demlight.COMMANDS)))
    dem_path = _os.fspath(dem_path)  # pathlib.Path too: the workers' tasks take a string
    if out_path is not None:
        out_path = _os.fspath(out_path)
    if client is None:
        from distributed import get_client
        client = get_client()
    from distributed import as_completed

    arguments = _demlight._arguments(product, options)
    call = _core.parse(product, arguments)
    dem = _demlight.open(dem_path, z_unit=call.z_unit or None, z_factor=call.z_factor or None)
    parts = windows(call.extent(dem._dem), chunks)
    if out_path is None:
        return _arrays(client, product, dem_path, arguments, parts)
    command_line = "demlight.dask.run(%r, %r, %r, chunks=%r%s)" % (
        product, dem_path, out_path, chunks, "".join(", %s=%r" % kv for kv in options.items()))
    writer = _core.Writer(call, dem._dem, str(out_path), _demlight._output_format(product, format),
                          _demlight._creation_options(creation_options), command_line, output_keyword="out_path")
    futures = client.map(_compute, [product] * len(parts), [dem_path] * len(parts), [arguments] * len(parts), parts,
                         pure=False)
    index = {f.key: i for i, f in enumerate(futures)}
    try:
        # The first window first: the files take their metadata from the first window written,
        # as the command line's tiles do; the others in the order they finish.
        writer.write(parts[0], futures[0].result())
        done = 1
        if progress is not None:
            progress(done / len(parts), "windows")
        for future in as_completed(futures[1:]):
            writer.write(parts[index[future.key]], future.result())
            future.release()
            done += 1
            if progress is not None and progress(done / len(parts), "windows") is False:
                raise _demlight.Cancelled("cancelled")
        return writer.commit()
    except BaseException:
        writer.abandon()
        client.cancel(futures)
        raise


def _band(rasters, name):
    for raster in rasters:
        if name in raster.bands:
            return raster.bands[name]
    raise KeyError(name)


def _arrays(client, product, dem_path, arguments, parts):
    """Band name -> dask array of the windows' tasks (run's out_path None)."""
    import dask
    import dask.array as da

    first = client.submit(_compute, product, dem_path, arguments, parts[0], pure=False).result()
    bands = {name: values.dtype for raster in first for name, values in raster.bands.items()}
    rows = {}
    for window in parts:
        rows.setdefault(window[1], []).append(window)
    arrays = {}
    tasks = {w: dask.delayed(_compute, pure=True)(product, dem_path, arguments, w) for w in parts}
    for name, dtype in bands.items():
        blocks = [[da.from_delayed(dask.delayed(_band, pure=True)(tasks[w], name), (w[3] - w[1], w[2] - w[0]), dtype)
                   for w in row] for _, row in sorted(rows.items())]
        arrays[name] = da.block(blocks)
    return arrays
