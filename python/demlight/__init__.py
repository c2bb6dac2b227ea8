"""demlight: light real terrain (DEMs) from Python.

    import demlight
    dem = demlight.open("samples/mount_st_helens_1980_usgs.dem")
    r = demlight.sun(dem, time="2024-06-21T07:30", tz="America/Los_Angeles")
    r.bands["sun_visibility"]          # numpy array, NaN = nodata
    r.write("sun.tif")                 # what `demlight sun ... -o sun.tif` writes

One function per raster command of the command line (horizon, sun, sky, aperture, light,
irradiance, insolation, sunhours), taking a DEM (from demlight.open or demlight.from_array), a
path, a numpy array with transform= (GDAL's 6 numbers or an affine.Affine) and crs=, or a
rioxarray DataArray, and the command's options as keyword arguments: the same names
(underscores for dashes), defaults, units and checks, parsed by the command line's own parser.
demlight.sunpos(time, lat, lon, ...) is `demlight sunpos --json` as a dict. Errors raise
demlight.Error with the library's message; an unknown keyword raises TypeError. Full
documentation: docs/python.md.
"""

import datetime as _datetime
import functools as _functools
import inspect as _inspect
import json as _json
import numbers as _numbers
import textwrap as _textwrap


def _module_mismatch(error):
    """Why the module _demlight did not import, in words: a module built for another Python
    fails as a 'partially initialized module (circular import)', which names neither."""
    import pathlib
    import re
    import sys
    import sysconfig

    here = pathlib.Path(__file__).resolve().parent
    this = "Python %d.%d" % sys.version_info[:2]
    built = sorted(p.name for p in here.glob("_demlight.*") if p.suffix in (".so", ".pyd"))
    wanted = "_demlight" + (sysconfig.get_config_var("EXT_SUFFIX") or "")
    if wanted in built:  # built for this Python, but it did not load (a missing library, ...)
        return "demlight's module %s did not load: %s" % (here / wanted, error)
    rebuild = ("build it for this one: `%s -m pip install .` in demlight's source tree (docs/python.md)"
               % (sys.executable or "python3"))
    if not built:
        return "demlight's module _demlight is not in %s (%s); %s" % (here, error, rebuild)
    versions = []
    for name in built:
        m = re.search(r"\.cpython-3(\d+)", name)
        versions.append("Python 3.%s (%s)" % (m.group(1), name) if m else name)
    return "demlight's module in %s was built for %s, and this is %s (%s): %s" % (
        here, " and ".join(versions), this, sys.executable, rebuild)


try:
    from . import _demlight
except ImportError as _error:
    raise ImportError(_module_mismatch(_error)) from None

try:
    import numpy as _numpy  # bands are numpy arrays, and arrays are DEMs
except ImportError as _error:
    import sys as _sys

    raise ImportError("demlight needs numpy, which this Python (%s, %s) cannot import: install it "
                      "(`%s -m pip install numpy`, or Debian's python3-numpy for /usr/bin/python3)"
                      % (_sys.executable, _sys.version.split()[0], _sys.executable)) from None

__version__ = _demlight.version
__all__ = ["Error", "Cancelled", "Dem", "Result", "open", "from_array", "horizon_profile", "COMMANDS"]

Error = _demlight.Error
Error.__doc__ = "Any failure demlight reports: bad input, bad option, unwritable output (the library's message)."
Cancelled = _demlight.Cancelled
Cancelled.__doc__ = "The work was stopped: a progress callback returned False."

#: The raster commands, one function each.
COMMANDS = tuple(_demlight.raster_commands())

# Options applied when a DEM is opened (demlight.open), not by a product on an open DEM.
_OPEN_KEYWORDS = ("z_unit", "z_factor")


class Dem:
    """A DEM opened for lighting (demlight.open, demlight.from_array).

    Attributes: width, height (cells), transform (GDAL geotransform, 6 numbers), crs (WKT),
    nodata (the band's nodata value or None), epsg, path (the file, or None for an array).
    heights: the heights in metres as a read-only numpy array (rows, columns), NaN = nodata
    (read from the file when first asked for). info(): what `demlight info --json` prints.
    """

    def __init__(self, handle):
        self._dem = handle

    width = property(lambda self: self._dem.width)
    height = property(lambda self: self._dem.height)
    transform = property(lambda self: self._dem.transform)
    crs = property(lambda self: self._dem.crs)
    nodata = property(lambda self: self._dem.nodata)
    epsg = property(lambda self: self._dem.epsg)
    path = property(lambda self: self._dem.path or None)

    @property
    def heights(self):
        return self._dem.heights()

    def info(self):
        """What `demlight info DEM --json` prints, as a dict."""
        return _json.loads(self._dem.info_json())

    def __repr__(self):
        return "<demlight.Dem %s, %d x %d cells>" % (self._dem.name, self.width, self.height)


def open(path, z_unit=None, z_factor=None, progress=None):  # noqa: A001 (as rasterio.open)
    """Opens a DEM: any raster GDAL reads (band 1), /vsizip/ and other virtual paths included.

    z_unit: vertical unit of the heights instead of the band's own (m, ft, US survey foot, cm,
    dm, mm, km); z_factor: metres per height unit instead (after the band's scale and offset).
    progress: callback(fraction, stage) of the opening pass on large DEMs; returning False
    stops it (demlight.Cancelled). Raises demlight.Error on a DEM demlight cannot light.
    """
    return Dem(_demlight.open(str(path), z_unit or "", float(z_factor or 0), progress))


def from_array(heights, transform=None, crs=None, nodata=None, name=None, z_unit=None, z_factor=None):
    """A DEM from a 2-D numpy array of heights (rows, columns), as a file holding them reads.

    transform: GDAL geotransform (x0, dx, 0, y0, 0, dy), north-up (dy < 0), or an
    affine.Affine (rasterio's, rioxarray's rio.transform()); crs: WKT, a definition GDAL reads
    such as "EPSG:32610", an EPSG code (32610) or a pyproj/rasterio CRS; nodata: the value
    marking no data (NaN always does); name: how outputs' DEMLIGHT_INPUT and messages name it
    (default "<array>"). The values are converted to Float32, as demlight reads every DEM.

    heights may also be an xarray.DataArray with rioxarray's georeference (rioxarray.open_rasterio,
    one band): its transform, CRS, nodata and unit ('units', as z_unit) are used, those given
    here take precedence, and name defaults to the file it was read from.
    """
    if _is_data_array(heights):
        heights, transform, crs, nodata, name, z_unit = _from_data_array(heights, transform, crs, nodata, name,
                                                                         z_unit, z_factor)
    if transform is None or crs is None:
        raise Error("a numpy array needs transform= (GDAL geotransform or affine.Affine) and crs=")
    if isinstance(crs, _numbers.Integral) and not isinstance(crs, bool):
        crs = "EPSG:%d" % crs  # a bare EPSG code, as rasterio and pyproj take it
    elif hasattr(crs, "to_wkt"):
        crs = crs.to_wkt()  # a pyproj or rasterio CRS object
    return Dem(_demlight.from_array(heights, _gdal_transform(transform), str(crs), nodata, name or "<array>",
                                    z_unit or "", float(z_factor or 0)))


def _gdal_transform(transform):
    """GDAL's 6 numbers of a geotransform given as those numbers or as an affine.Affine, whose
    own order (a, b, c, d, e, f, and 0, 0, 1: 9 numbers) is not GDAL's."""
    if hasattr(transform, "to_gdal"):
        transform = transform.to_gdal()
    return [float(v) for v in transform]


def _is_data_array(obj):
    return type(obj).__name__ == "DataArray" and type(obj).__module__.split(".")[0] == "xarray"


def _from_data_array(da, transform, crs, nodata, name, z_unit, z_factor):
    """heights, transform, crs, nodata, name and z_unit of a DataArray DEM (rioxarray's
    georeference; the arguments given take precedence)."""
    if da.ndim == 3 and da.shape[0] == 1:  # open_rasterio's (band, y, x) of a one-band raster
        da = da[0]
    if da.ndim != 2:
        raise Error("a DataArray DEM: expected (y, x) or one band, got dimensions %s" % (da.dims,))
    scale, offset = da.attrs.get("scale_factor", 1.0), da.attrs.get("add_offset", 0.0)
    if scale != 1 or offset != 0:
        raise Error("a DataArray DEM with scale_factor %r and add_offset %r not applied: open it with "
                    "rioxarray.open_rasterio(path, mask_and_scale=True)" % (scale, offset))
    if transform is None or crs is None:
        try:
            import rioxarray  # noqa: F401 (registers .rio)
        except ImportError:
            raise Error("a DataArray DEM: its georeference is read with rioxarray (python3-rioxarray), "
                        "which is not installed; give transform= and crs=") from None
        if transform is None:
            transform = da.rio.transform()
        if crs is None:
            crs = da.rio.crs
            if crs is None:
                raise Error("a DataArray DEM without a CRS: give crs= or set one with da.rio.write_crs(...)")
    if nodata is None:
        try:
            import rioxarray  # noqa: F401
            value = da.rio.nodata
            if value is not None and value != value:  # masked=True: NaN cells for the file's value,
                value = da.rio.encoded_nodata         # which outputs carry as a file's DEM's do
        except ImportError:
            value = da.attrs.get("_FillValue")
        if value is not None and value == value:
            nodata = float(value)
    if name is None:
        name = da.encoding.get("source")
    if z_unit is None and z_factor is None and da.attrs.get("units"):
        z_unit = str(da.attrs["units"])  # the band's vertical unit, as opening the file reads it
    return _numpy.asarray(da.values), transform, crs, nodata, name, z_unit

def horizon_profile(dem, at=None, at_xy=None, directions=48, azimuth_origin="north", max_distance=None,
                    refraction=None, transform=None, crs=None, nodata=None):
    """The horizon profile at one point, as `demlight horizon DEM --at LAT,LON` computes it (the
    reference ray march at the point's cell), for solar tools: a pair of numpy float64 arrays
    (azimuths, elevations), in degrees.

    Azimuths: `directions` of them, evenly spaced, the first due north (48: every 7.5 degrees, as
    PVGIS and pvlib profiles). azimuth_origin="north": degrees clockwise from true north (0 = N,
    90 = E, 180 = S), pvlib's convention and that of PVGIS's user horizon upload;
    azimuth_origin="south": PVGIS's own horizon output convention (0 = S, 90 = W, -90 = E, in
    [-180, 180); north is -180), the same order. Elevations: the horizon's angle above the
    local horizontal plane (negative where the point looks down on its surroundings).

    dem: as the raster commands take it (a demlight.Dem, a path, or a numpy array with
    transform=, crs=, nodata=). at: (latitude, longitude) in WGS84 degrees; or at_xy: (x, y) in
    the DEM's CRS. max_distance (metres) and refraction: as `demlight horizon` takes them (None =
    its defaults).
    """
    if (at is None) == (at_xy is None):
        raise Error("horizon_profile: give at=(lat, lon) or at_xy=(x, y)")
    if azimuth_origin not in ("north", "south"):
        raise Error("horizon_profile: azimuth_origin %r: expected 'north' or 'south'" % (azimuth_origin,))
    if isinstance(directions, bool) or not isinstance(directions, _numbers.Integral) or directions < 1:
        raise Error("horizon_profile: directions %r: expected a whole number >= 1" % (directions,))
    if refraction is None:
        refraction = _default(_options("horizon")["refraction"])
    opened = _as_dem(dem, transform, crs, nodata, {})
    first, second = at if at is not None else at_xy
    azimuths, elevations = _demlight.horizon_profile(opened._dem, float(first), float(second), at is not None,
                                                     int(directions), None if max_distance is None
                                                     else float(max_distance), float(refraction),
                                                     azimuth_origin == "south")
    return azimuths, elevations


def _creation_options(options):
    """GDAL KEY=VALUE items as a list: one given as a string is one item, not its characters."""
    return [options] if isinstance(options, str) else list(options)


def _as_dem(dem, transform, crs, nodata, options):
    """The DEM a product runs on: `dem` itself, opened from a path, or made from an array or a
    DataArray, with the options that apply when a DEM is opened (z_unit, z_factor)."""
    opening = {k: options.pop(k) for k in _OPEN_KEYWORDS if k in options}
    if isinstance(dem, Dem):
        if opening:
            raise Error("%s: applies when the DEM is opened: demlight.open(path, %s=...)"
                        % (", ".join(opening), next(iter(opening))))
        if transform is not None or crs is not None:
            raise Error("transform and crs are for numpy arrays; this DEM has its own")
        return dem
    if isinstance(dem, (str, bytes)) or hasattr(dem, "__fspath__"):
        if transform is not None or crs is not None:
            raise Error("transform and crs are for numpy arrays; a file has its own")
        return open(dem, **opening)
    if not _is_data_array(dem) and (transform is None or crs is None):
        raise Error("a numpy array needs transform= (GDAL geotransform or affine.Affine) and crs=")
    return from_array(dem, transform, crs, nodata=nodata, **opening)


def _option_text(name, value):
    if isinstance(value, _datetime.date):  # an aware datetime carries its offset; a naive one needs tz=
        return value.isoformat()
    if isinstance(value, _datetime.timedelta):
        seconds = value.total_seconds()
        if seconds != int(seconds):
            raise Error("%s: %r is not a whole number of seconds" % (name, value))
        return "%ds" % int(seconds)
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _arguments(command, options):
    """The keywords of a call as the library takes them: (keyword, [values as text]) in the order
    given, None (the default) left out; unknown keywords raise TypeError."""
    spec = _options(command)
    keywords = []
    for name, value in options.items():
        if name not in spec:
            raise _unknown_keyword(command, name, spec)
        if value is None:
            continue
        if spec[name]["flag"]:
            if value:
                keywords.append((name, []))
        elif isinstance(value, (list, tuple)):
            keywords.append((name, [_option_text(name, v) for v in value]))
        else:
            keywords.append((name, [_option_text(name, value)]))
    return keywords


def _unknown_keyword(command, name, known):
    """The TypeError Python raises for an unexpected keyword, with the nearest known name."""
    import difflib

    close = difflib.get_close_matches(name, sorted(known), n=1)
    hint = " (did you mean %s?)" % close[0] if close else ""
    return TypeError("demlight.%s() got an unexpected keyword argument '%s'%s; its keywords: %s"
                     % (command, name, hint, ", ".join(sorted(set(known)))))


def _output_format(command, value):
    """`value` spelt as the output format it names in any case ('cog' is 'COG'); anything else as
    given, for the writer to refuse."""
    for o in _declaration(command)["options"]:
        if o["name"] == "format":
            for choice in o["choices"]:
                if str(value).lower() == choice.lower():
                    return choice
    return str(value)


def _command_line(command, dem, options):
    """DEMLIGHT_COMMAND of a Python run: the call as Python code."""
    what = repr(dem.path) if dem.path else dem._dem.name  # an array: its name
    parts = [what] + ["%s=%r" % kv for kv in options.items()]
    return "demlight.%s(%s)" % (command, ", ".join(parts))


class Result:
    """What a command computed: its bands and metadata, on the DEM's (or srcwin's) georeference.

    bands: dict band name -> numpy array (rows, columns); Float32 bands hold NaN at nodata,
    Byte bands (masks) their own nodata value. units: band name -> unit. metadata: the DEMLIGHT_*
    items the command line writes (but DEMLIGHT_COMMAND, which write adds). transform, crs:
    where the bands sit. rasters: the command's output rasters (horizon: the horizons and the
    truncation mask, which write() puts in two files as the command line does).
    """

    def __init__(self, command, rasters, call, dem, options):
        self.command = command
        self.rasters = list(rasters)
        self._call = call
        self._dem = dem
        self._options = dict(options)

    @property
    def bands(self):
        out = {}
        for r in self.rasters:
            out.update(r.bands)
        return out

    @property
    def units(self):
        out = {}
        for r in self.rasters:
            out.update(r.units)
        return out

    @property
    def metadata(self):
        return dict(self.rasters[0].metadata)

    transform = property(lambda self: self.rasters[0].transform)
    crs = property(lambda self: self.rasters[0].crs)
    nodata = property(lambda self: self.rasters[0].nodata)

    def write(self, path, format="GTiff", creation_options=()):  # noqa: A002 (the command line's name)
        """Writes the result as `demlight <command> ... -o path` does and returns the paths written.

        format: "GTiff" (tiled, ZSTD) or "COG", in any case; creation_options: GDAL KEY=VALUE items (-co).
        Atomic: a temporary name renamed on success; refuses to overwrite the input DEM.
        DEMLIGHT_COMMAND records the Python call.
        """
        return self._call.write(self.rasters, str(path), _output_format(self.command, format),
                                _creation_options(creation_options),
                                _command_line(self.command, self._dem, self._options), self._dem._dem.path)

    def to_xarray(self):
        """The bands as an xarray.Dataset on x/y cell-centre coordinates, each variable's unit
        in attrs["units"]; with rioxarray installed, the CRS, transform and nodata are attached
        (ds.rio), so ds.rio.to_raster(path) writes every band into one GeoTIFF, and
        ds[band].rio.to_raster(path) one band.

        A GeoTIFF has one nodata value for all its bands, so the bands of the rasters that
        Result.write puts in files of their own (horizon's uint8 truncation masks) are float32
        here, NaN at their nodata cells (0 and 1 elsewhere), encoded with the first raster's
        nodata value as its own bands are; r.bands keeps them uint8."""
        import numpy as np
        import xarray as xr

        gt = self.transform
        first = next(iter(self.bands.values()))
        rows, cols = first.shape
        x = gt[0] + (np.arange(cols) + 0.5) * gt[1]
        y = gt[3] + (np.arange(rows) + 0.5) * gt[5]
        variables = {}
        for raster in self.rasters:
            for name, values in raster.bands.items():
                if values.dtype.kind != "f":
                    values = np.where(values == raster.nodata, np.float32(np.nan), values.astype(np.float32))
                attrs = {"units": raster.units[name]}
                variables[name] = xr.DataArray(values, dims=("y", "x"), coords={"y": y, "x": x}, attrs=attrs)
        ds = xr.Dataset(variables, attrs=self.metadata)
        try:
            import rioxarray  # noqa: F401 (registers .rio)
            from affine import Affine
        except ImportError:
            ds.attrs["crs_wkt"] = self.crs
            ds.attrs["transform"] = tuple(gt)
            for name in ds.data_vars:
                ds[name].attrs["nodata"] = self.nodata
            return ds
        ds = ds.rio.write_crs(self.crs)
        ds = ds.rio.write_transform(Affine.from_gdal(*gt))
        # The cells hold NaN where the file holds the nodata value: the value is the encoding
        # (rio.encoded_nodata; rio.nodata is NaN), so rio.to_raster writes it where NaN is, as
        # Result.write does.
        for name in ds.data_vars:
            ds[name] = ds[name].rio.write_nodata(self.nodata, encoded=True)
        return ds

    def __repr__(self):
        return "<demlight.Result %s: %s>" % (self.command, ", ".join(self.bands))


@_functools.lru_cache(maxsize=None)
def _declarations():
    return {c["name"]: c for c in _json.loads(_demlight.options_json())["commands"]}


def _declaration(command):
    """The command's declaration (demlight/run/parameters.h) as JSON: name, description, and its
    options with keyword, aliases, label, unit, python_help, type, choices, range, default, ..."""
    try:
        return _declarations()[command]
    except KeyError:
        raise Error("no command '%s'" % command) from None


def _command_options(command):
    """The options of `command` that are Python keywords, in their declared order."""
    return [o for o in _declaration(command)["options"] if "python" in o["front_ends"]]


@_functools.lru_cache(maxsize=None)
def _options(command):
    """Keyword name (aliases included) -> the option's declaration."""
    spec = {}
    for o in _command_options(command):
        for k in [o["keyword"]] + o["aliases"]:
            spec[k] = o
    return spec


def _run(command, dem, transform=None, crs=None, nodata=None, progress=None, **options):
    call = _demlight.parse(command, _arguments(command, options))
    opened = _as_dem(dem, transform, crs, nodata, {k: options[k] for k in _OPEN_KEYWORDS if k in options})
    rasters = call.compute(opened._dem, progress)
    return Result(command, rasters, call, opened, {k: v for k, v in options.items() if k not in _OPEN_KEYWORDS})


#: Each command's bands with their units (Result.units) under its default options, and what
#: options change; tests/python checks the table against the products.
BANDS = {
    "horizon": ([("horizon_azimuth=<deg>", "deg"),
                 ("truncated_azimuth=<deg>", "")],
                "One horizon elevation band per azimuth (degrees above the horizontal), and one uint8 "
                "truncation mask per azimuth: 1 where the "
                "search reached the DEM edge before max_distance, 0 elsewhere, 255 at DEM voids "
                "(Result.write puts the masks in OUT.truncated.tif)."),
    "sun": ([("sun_visibility", "fraction of sun disk (0-1)"),
             ("sun_irradiance", "normalised irradiance (1 = unit-radiance zenith sun on flat ground)")],
            "model='aperture' or 'aperture-smooth': the same bands, sun_visibility the fraction of "
            "the sun cap inside the aperture cap (0-1)."),
    "sky": ([("svf_horizontal", "fraction (cosine-weighted, horizontal plane)"),
             ("sky_fraction", "fraction of the upper hemisphere"),
             ("sky_K", "normalised irradiance from a unit-radiance sky"),
             ("sky_factor", "normalised irradiance with interreflection")],
            "Other model values write other bands (docs/commands.md, sky)."),
    "aperture": ([("bent_normal_east", "unit vector component (ENU)"),
                  ("bent_normal_north", "unit vector component (ENU)"),
                  ("bent_normal_up", "unit vector component (ENU)"),
                  ("aperture_radius_deg", "deg"),
                  ("visible_solid_angle_sr", "sr")], ""),
    "light": ([("light", "normalised irradiance (1 = unit zenith sun, or unit sky, on open flat ground)")],
              "sun_color or sky_color: light_r, light_g, light_b; color_raster: reflected_r, "
              "reflected_g, reflected_b (docs/commands.md, light)."),
    "irradiance": ([("beam", "W m-2"), ("diffuse", "W m-2"), ("reflected", "W m-2"), ("global", "W m-2")], ""),
    "insolation": ([("beam", "kWh m-2"), ("diffuse", "kWh m-2"), ("reflected", "kWh m-2"), ("global", "kWh m-2"),
                    ("sun_hours", "hours")], ""),
    "sunhours": ([("sun_hours", "hours of direct sun weighted by visibility (h)"),
                  ("sun_irradiation", "normalised irradiance x hours (1 h of unit zenith sun on flat ground = 1)"),
                  ("sky_irradiation", "f_sky x daylight hours: a unit uniform sky from sunrise to sunset at the "
                                      "cell (1 h of unit sky on open flat ground = 1)"),
                  ("first_lit", "local clock hours (<tz>) when half the sun first shows; -1 = never"),
                  ("last_lit", "local clock hours (<tz>) when half the sun last shows; -1 = never")], ""),
}


def _bands_doc(command):
    if command not in BANDS:
        return []
    bands, note = BANDS[command]
    lines = ["Bands (Result.bands, in this order; Result.units holds each unit):"]
    for name, unit in bands:
        lines += _textwrap.wrap("%s: %s" % (name, unit or "mask, see below"), 92, initial_indent="    ",
                                subsequent_indent="        ")
    if note:
        lines += _textwrap.wrap(note, 92, initial_indent="    ", subsequent_indent="    ")
    return lines + [""]


_TYPES = {"FLOAT": float, "UINT": int, "INT": int}


def _default(o):
    text = o["default"]
    if text is None or o["flag"]:
        return None
    kind = _TYPES.get(o["type"], str)
    try:
        return kind(text)
    except ValueError:
        return text


def _option_doc(o):
    """An option's lines in a docstring: keyword (aliases) : type, unit, default; its help."""
    head = o["keyword"]
    if o["aliases"]:
        head += " (also %s)" % ", ".join(o["aliases"])
    if o["required"]:
        head += ", required"
    if o["type"]:
        head += " : %s" % o["type"].lower()
        if o["max_values"] > 1:
            head += " x %d" % o["max_values"]
        elif o["max_values"] < 0:
            head += " (a sequence)"
    if o["unit"]:
        head += " [%s]" % o["unit"]
    if o["choices"]:
        head += ", one of %s" % ", ".join(o["choices"])
    if o["default"] is not None:
        head += ", default %s" % o["default"]
    return [head] + _textwrap.wrap(o["python_help"], 92, initial_indent="    ", subsequent_indent="    ")


def _docstring(command):
    lines = [
        "%s (demlight %s)." % (_declaration(command)["description"], command),
        "",
        "demlight.%s(dem, *, transform=None, crs=None, nodata=None, progress=None, **options) -> Result" % command,
        "",
        "dem: a demlight.Dem (demlight.open, demlight.from_array), a path GDAL opens, a 2-D",
        "numpy array of heights in metres with transform= (GDAL geotransform or affine.Affine),",
        "crs= (WKT, 'EPSG:n', n or a CRS object) and nodata=, or an xarray.DataArray with",
        "rioxarray's georeference. progress: callback(fraction, stage), called from the work's",
        "threads with the GIL held; returning False raises demlight.Cancelled. Ctrl-C stops the",
        "work (KeyboardInterrupt). The GIL is released while demlight computes.",
        "",
        "Options: those of `demlight %s` (its --help), as keywords; the same" % command,
        "defaults, units and checks. Times: ISO 8601 strings with an offset or Z, local times with",
        "tz=, or timezone-aware datetime objects; days: 'YYYY-MM-DD' or datetime.date; steps:",
        "'10m', '90s' or datetime.timedelta. Lists (azimuth, srcwin) as Python sequences.",
        "",
    ] + _bands_doc(command)
    for o in _command_options(command):
        lines += _option_doc(o)
    lines += ["", "Returns a demlight.Result: .bands, .units, .metadata, .write(path), .to_xarray().",
              "Raises demlight.Error with the library's message (options named as keywords)."]
    return "\n".join(lines)


def _make_command(command):
    def product(dem, *, transform=None, crs=None, nodata=None, progress=None, **options):
        return _run(command, dem, transform=transform, crs=crs, nodata=nodata, progress=progress, **options)

    product.__name__ = product.__qualname__ = command
    product.__doc__ = _docstring(command)
    params = [_inspect.Parameter("dem", _inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    for name in ("transform", "crs", "nodata", "progress"):
        params.append(_inspect.Parameter(name, _inspect.Parameter.KEYWORD_ONLY, default=None))
    for o in _command_options(command):
        params.append(_inspect.Parameter(o["keyword"], _inspect.Parameter.KEYWORD_ONLY, default=_default(o)))
    product.__signature__ = _inspect.Signature(params)
    return product


for _command in COMMANDS:
    globals()[_command] = _make_command(_command)
    __all__.append(_command)
del _command


def sunpos(time, lat, lon, **options):
    return _json.loads(_demlight.sunpos_json(_arguments("sunpos", dict(time=time, lat=lat, lon=lon, **options))))


def _sunpos_signature():
    params = []
    for o in _command_options("sunpos"):
        if o["required"]:
            params.append(_inspect.Parameter(o["keyword"], _inspect.Parameter.POSITIONAL_OR_KEYWORD))
        else:
            params.append(_inspect.Parameter(o["keyword"], _inspect.Parameter.KEYWORD_ONLY, default=_default(o)))
    return _inspect.Signature(sorted(params, key=lambda p: p.kind))


def _sunpos_doc():
    lines = ["%s (demlight sunpos)." % _declaration("sunpos")["description"], "",
             "demlight.sunpos%s -> dict" % _sunpos_signature(), ""]
    for o in _command_options("sunpos"):
        lines += _option_doc(o)
    lines += ["", "time also as a timezone-aware datetime. Returns what `demlight sunpos --json` prints, as a dict:",
              "utc, local, zone (the instant and its zone); latitude_deg, longitude_deg, elevation_m,",
              "pressure_hpa, temperature_c (the site); zenith_deg and elevation_deg (topocentric,",
              "refracted), azimuth_deg (clockwise from true north), geometric_elevation_deg,",
              "refraction_deg, declination_deg, equation_of_time_min, delta_t_s and delta_t_source;",
              "day (the local day), sunrise, transit, sunset (ISO 8601 on the zone's clocks, whole",
              "seconds; sunrise and sunset None on a polar day or night), polar ('day', 'night' or",
              "None). Raises demlight.Error with the command's message (options named as keywords)."]
    return "\n".join(lines)


sunpos.__signature__ = _sunpos_signature()
sunpos.__doc__ = _sunpos_doc()
__all__ += ["sunpos", "BANDS"]

