#!/usr/bin/python3
"""Runs a raster command through demlight.dask on a LocalCluster and through the command line,
and prints both wall times and whether the files are the same (gdalinfo -checksum of every band
and the DEMLIGHT_* metadata but DEMLIGHT_COMMAND). docs/python.md quotes its figures.

Usage: scripts/dask_compare.py DEM CHUNKS WORKERS COMMAND [--flag value ...]
e.g.   scripts/dask_compare.py ../shared/data/dem/svalbard_longyearbyen_npi_dtm20.tif 512 2 sun --time 2024-06-21T07:30:00Z
"""
import os
import subprocess
import sys
import tempfile
import time

import distributed

import demlight.dask


def facts(path):
    out = subprocess.run(["gdalinfo", "-checksum", path], check=True, capture_output=True, text=True).stdout
    return [line for line in out.splitlines() if "Checksum=" in line or ("DEMLIGHT_" in line and "DEMLIGHT_COMMAND" not in line)]


def main():
    dem, chunks, workers, command, flags = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5:]
    options = {flags[i].lstrip("-").replace("-", "_"): flags[i + 1] for i in range(0, len(flags), 2)}
    cli = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "release", "cli", "demlight")
    with tempfile.TemporaryDirectory() as folder:
        with distributed.LocalCluster(n_workers=workers, threads_per_worker=1, dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            start = time.monotonic()
            written = demlight.dask.run(command, dem, os.path.join(folder, "dask.tif"), chunks=chunks, client=client,
                                        **options)
            dask_seconds = time.monotonic() - start
        start = time.monotonic()
        subprocess.run([cli, "-q", command, dem, "-o", os.path.join(folder, "cli.tif"), *flags], check=True)
        cli_seconds = time.monotonic() - start
        opened = demlight.open(dem)
        windows = len(demlight.dask.windows((0, 0, opened.width, opened.height), chunks))
        same = all(facts(p) == facts(p.replace("dask.", "cli.")) for p in written)
        print("%s on %s: demlight.dask %d windows on %d workers %.2f s, command line %.2f s, files %s"
              % (command, os.path.basename(dem), windows, workers, dask_seconds, cli_seconds,
                 "identical" if same else "DIFFERENT"))
        return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
