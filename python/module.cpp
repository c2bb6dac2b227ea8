// demlight._demlight: the C++ side of the Python package (python/demlight/). DEMs opened from
// files or made from numpy arrays; a raster command's keywords set through the command's
// declaration (demlight/run/parameters.h) into its work (demlight/run/), so names, defaults,
// checks and messages are the command's, spelt as keywords; results as numpy views; the runner's
// writers (one piece, or window by window for demlight.dask); sunpos's report as JSON. Work runs
// without the GIL; progress callbacks take it back.
#include "demlight/run/raster_commands.h"
#include "demlight/run/runner.h"
#include "demlight/run/sunpos_command.h"
#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/products/horizon.h"
#include "demlight/products/point.h"
#include "demlight/products/product.h"
#include "demlight/products/tiles.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace py = pybind11;

namespace demlight::python {
namespace {

// ---- Errors and progress ------------------------------------------------------------------------

/// A message of the library with its parameters spelt as Python keywords (of `set`, the running
/// command's, when known); the output raster as `outputKeyword`, the name of the path argument
/// of the call that writes it (Result.write's path, demlight.dask.run's out_path).
Error keywordError(const std::exception& e, const ParameterSet* set, const std::string& outputKeyword = "path") {
    const auto* named = dynamic_cast<const ParameterError*>(&e);
    if (!named) return Error(describeError(e, set, Naming::Python));
    return Error(renderNames(named->text(), [&](const std::string& name) {
        return name == "output" ? outputKeyword : renderNames("{" + name + "}", set, Naming::Python);
    }));
}

/// Runs library work without the GIL, and cancels it when Python asks: the progress callback
/// raises or returns False, or a signal handler raises (Ctrl-C: KeyboardInterrupt). The raised
/// exception is raised again once the library has unwound; a callback returning False raises
/// demlight.Cancelled.
class PythonProgress {
public:
    explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}

    template <class Work>
    auto run(Work&& work) -> decltype(work(ProgressFn{})) {
        std::optional<decltype(work(ProgressFn{}))> result;
        try {
            py::gil_scoped_release release;
            result.emplace(work(fn()));
        } catch (const Cancelled&) {
            if (!error_) throw;
        }
        if (error_) {
            py::error_already_set e = std::move(*error_);
            error_.reset();
            throw e;
        }
        return std::move(*result);
    }

private:
    /// Called from any thread of the library (one at a time: ProgressCounter serialises them).
    ProgressFn fn() {
        return [this](double fraction, const std::string& stage) {
            py::gil_scoped_acquire gil;
            if (error_) return false;
            if (PyErr_CheckSignals() != 0) {
                error_ = std::make_unique<py::error_already_set>();
                return false;
            }
            if (callback_.is_none()) return true;
            try {
                const py::object answer = callback_(fraction, stage);
                return answer.is_none() || answer.cast<bool>();
            } catch (py::error_already_set& e) {
                error_ = std::make_unique<py::error_already_set>(std::move(e));
                return false;
            }
        };
    }

    py::object callback_;
    std::unique_ptr<py::error_already_set> error_;
};

// ---- DEMs ------------------------------------------------------------------------------------

/// A DEM as Python holds it: the source products read windows from, and how it was opened.
struct PyDem {
    std::shared_ptr<const DemSource> source;
    /// The file it was opened from (empty for an array): DEMLIGHT_INPUT, and the input an output
    /// must not overwrite.
    std::string path;
    mutable std::shared_ptr<const Dem> whole;  ///< the heights, read when first asked for

    const Dem& geometry() const { return source->geometry(); }
};

/// A read-only numpy view of `grid`, keeping `owner` alive.
template <class T, class Owner>
py::array view(const Grid<T>& grid, const std::shared_ptr<Owner>& owner) {
    auto* keep = new std::shared_ptr<Owner>(owner);
    py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<Owner>*>(p); });
    py::array a(py::dtype::of<T>(), {grid.height(), grid.width()}, {grid.width() * sizeof(T), sizeof(T)}, grid.data(),
                base);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

py::tuple transformTuple(const GeoReference& ref) {
    const auto& g = ref.geoTransform;
    return py::make_tuple(g[0], g[1], g[2], g[3], g[4], g[5]);
}

GeoReference geoReference(const std::vector<double>& transform, const std::string& crs) {
    if (transform.size() != 6)
        throw Error("transform: expected GDAL's 6 numbers (x0, dx, 0, y0, 0, dy), got " +
                    std::to_string(transform.size()));
    GeoReference ref;
    std::copy(transform.begin(), transform.end(), ref.geoTransform.begin());
    ref.crsWkt = crs;
    return ref;
}

HeightOptions heightOptions(const std::string& zUnit, double zFactor) {
    HeightOptions h;
    h.zUnit = zUnit;
    h.zFactor = zFactor;
    return h;
}

PyDem openPath(const std::string& path, const std::string& zUnit, double zFactor, py::object progress) {
    PythonProgress p(std::move(progress));
    const HeightOptions heights = heightOptions(zUnit, zFactor);
    auto source = p.run([&](const ProgressFn& fn) { return std::make_shared<const DemSource>(DemSource::open(path, heights, fn)); });
    return {std::move(source), path, nullptr};
}

PyDem fromArray(py::array_t<float, py::array::c_style | py::array::forcecast> heights, const std::vector<double>& transform,
                const std::string& crs, std::optional<double> nodata, const std::string& name, const std::string& zUnit,
                double zFactor) {
    if (heights.ndim() != 2) throw Error("heights: expected a 2-D array (rows, columns), got " + std::to_string(heights.ndim()) + " dimensions");
    Grid<float> values(static_cast<std::size_t>(heights.shape(1)), static_cast<std::size_t>(heights.shape(0)));
    std::copy_n(heights.data(), values.size(), values.data());
    const GeoReference ref = geoReference(transform, crs);
    const HeightOptions h = heightOptions(zUnit, zFactor);
    std::shared_ptr<const DemSource> source;
    {
        py::gil_scoped_release release;
        source = std::make_shared<const DemSource>(DemSource(demFromArray(values, ref, nodata, name, h)));
    }
    return {std::move(source), std::string(), nullptr};
}

// ---- Results ---------------------------------------------------------------------------------

/// One output raster of a product (a part of a command's result).
using Raster = ProductResult;

py::dict rasterBands(const std::shared_ptr<Raster>& r) {
    py::dict out;
    for (const ProductBand& b : r->bands)
        out[py::str(b.name)] = b.values.empty() ? view(b.flags, r) : view(b.values, r);
    return out;
}

/// State of a raster for pickling (demlight.dask moves window results from workers).
py::tuple rasterState(const Raster& r) {
    py::list bands;
    for (const ProductBand& b : r.bands) {
        const bool flags = b.values.empty();
        py::array cells = flags ? py::array(py::dtype::of<std::uint8_t>(), {b.flags.height(), b.flags.width()}, b.flags.data())
                                : py::array(py::dtype::of<float>(), {b.values.height(), b.values.width()}, b.values.data());
        bands.append(py::make_tuple(b.name, b.unit, flags, static_cast<int>(b.resampling), cells));
    }
    return py::make_tuple(bands, r.metadata, transformTuple(r.ref), r.ref.crsWkt, r.nodata, r.flagNodata);
}

template <class T>
Grid<T> gridOf(const py::array& a) {
    const auto cells = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!cells || cells.ndim() != 2) throw Error("raster state: expected a 2-D band");
    Grid<T> g(static_cast<std::size_t>(cells.shape(1)), static_cast<std::size_t>(cells.shape(0)));
    std::copy_n(cells.data(), g.size(), g.data());
    return g;
}

std::shared_ptr<Raster> rasterFromState(const py::tuple& t) {
    auto r = std::make_shared<Raster>();
    for (const py::handle item : t[0].cast<py::list>()) {
        const auto b = item.cast<py::tuple>();
        ProductBand band;
        band.name = b[0].cast<std::string>();
        band.unit = b[1].cast<std::string>();
        band.resampling = static_cast<Resampling>(b[3].cast<int>());
        if (b[2].cast<bool>())
            band.flags = gridOf<std::uint8_t>(b[4].cast<py::array>());
        else
            band.values = gridOf<float>(b[4].cast<py::array>());
        r->bands.push_back(std::move(band));
    }
    r->metadata = t[1].cast<std::map<std::string, std::string>>();
    r->ref = geoReference(t[2].cast<std::vector<double>>(), t[3].cast<std::string>());
    r->nodata = t[4].cast<double>();
    r->flagNodata = t[5].cast<std::optional<double>>();
    return r;
}

std::vector<const ProductResult*> pointers(const std::vector<std::shared_ptr<Raster>>& parts) {
    std::vector<const ProductResult*> out;
    for (const auto& p : parts) out.push_back(p.get());
    return out;
}

// ---- Calls -----------------------------------------------------------------------------------

/// The keywords of a call: (keyword, its values as text) in the order given; what demlight.dask
/// pickles to its workers.
using Keywords = std::vector<std::pair<std::string, std::vector<std::string>>>;

/// A raster command's work on any DEM (demlight/run/raster_commands.h), its keywords set through
/// the command's declaration.
struct PyCall {
    std::shared_ptr<RasterCommand> command;
    RasterWork work;

    const ParameterSet* declaration() const { return &command->declaration(); }
    std::size_t halo(const PyDem& dem) const { return named([&] { return work.halo(*dem.source); }); }
    /// The extent (the whole DEM or srcwin) and its tiles, as the command plans them.
    RasterRun plan(const PyDem& dem) const { return named([&] { return work.plan(*dem.source, RunContext{}); }); }
    /// f(), its errors' messages naming this command's keywords (the output as `outputKeyword`).
    template <class F>
    auto named(F&& f, const std::string& outputKeyword = "path") const -> decltype(f()) {
        try {
            return f();
        } catch (const Cancelled&) {
            throw;
        } catch (const Error& e) {
            throw keywordError(e, declaration(), outputKeyword);
        }
    }
};

/// The raster command `command` with these keywords set.
std::shared_ptr<PyCall> parseCall(const std::string& command, const Keywords& keywords) {
    auto out = std::make_shared<PyCall>();
    out->command = makeRasterCommand(command);
    out->work = out->named([&] {
        ParameterSet& set = out->command->declaration();
        for (const auto& [keyword, values] : keywords) set.set(keyword, values, kPython);
        set.checkRequired(kPython);
        return out->command->work();
    });
    return out;
}

/// The command on its extent (the whole DEM or srcwin) in the tiles it plans (tile_size,
/// memory_limit), pasted into one result per output raster: what the command line writes.
std::vector<std::shared_ptr<Raster>> computeCall(const PyCall& c, const PyDem& dem, py::object progress) {
    const RasterRun run = c.plan(dem);
    PythonProgress p(std::move(progress));
    return p.run([&](const ProgressFn& fn) {
        return c.named([&] {
            std::vector<std::shared_ptr<Raster>> out;
            for (ProductResult& part : computeRaster(c.work, *dem.source, run, fn))
                out.push_back(std::make_shared<Raster>(std::move(part)));
            return out;
        });
    });
}

/// One window of the DEM (cells of the whole DEM), as a tile of the command's job.
std::vector<std::shared_ptr<Raster>> computeWindow(const PyCall& c, const PyDem& dem, const std::vector<std::size_t>& w,
                                                   py::object progress) {
    if (w.size() != 4) throw Error("window: expected (col0, row0, col1, row1)");
    const CellWindow window{w[0], w[1], w[2], w[3]};
    PythonProgress p(std::move(progress));
    return p.run([&](const ProgressFn& fn) {
        return c.named([&] {
            std::vector<std::shared_ptr<Raster>> out;
            for (ProductResult& part : c.work.compute(*dem.source, window, fn))
                out.push_back(std::make_shared<Raster>(std::move(part)));
            return out;
        });
    });
}

OutputOptions outputOptions(const std::string& path, const std::string& format, const std::vector<std::string>& co) {
    OutputOptions out;
    out.path = path;
    out.format = format;
    out.creationOptions = co;
    return out;
}

/// Writes a command's results to the files -o `path` names (horizon: two), as the command line
/// does: all or none, DEMLIGHT_COMMAND = `commandLine`.
std::vector<std::string> writeCall(const PyCall& c, const std::vector<std::shared_ptr<Raster>>& parts, const std::string& path,
                                   const std::string& format, const std::vector<std::string>& co,
                                   const std::string& commandLine, const std::string& inputPath) {
    const std::vector<RasterTarget> targets = c.named([&] { return c.work.targets(outputOptions(path, format, co)); });
    RunContext ctx;
    ctx.commandLine = commandLine;
    {
        py::gil_scoped_release release;
        c.named([&] {
            for (const RasterTarget& t : targets) checkOutputPath(t.out, inputPath);
            writeResults(pointers(parts), targets, ctx, inputPath);
        });
    }
    std::vector<std::string> paths;
    for (const auto& t : targets) paths.push_back(t.out.path);
    return paths;
}

/// The command line's tiled writer: windows of the extent written into the files as they arrive,
/// renamed at commit; dropped without commit, nothing is left.
class PyWriter {
public:
    /// `outputKeyword`: how the caller names `path` (demlight.dask.run's out_path), in messages.
    PyWriter(std::shared_ptr<PyCall> call, const PyDem& dem, const std::string& path, const std::string& format,
             const std::vector<std::string>& co, const std::string& commandLine, std::string outputKeyword)
        : call_(std::move(call)), outputKeyword_(std::move(outputKeyword)) {
        ctx_.commandLine = commandLine;
        run_ = call_->plan(dem);
        call_->named([&] {
            targets_ = call_->work.targets(outputOptions(path, format, co));
            for (const RasterTarget& t : targets_) checkOutputPath(t.out, dem.path);
            writer_ = std::make_unique<TiledWriter>(run_, targets_, ctx_, dem.path);
        }, outputKeyword_);
    }
    void write(const std::vector<std::size_t>& w, const std::vector<std::shared_ptr<Raster>>& parts) {
        if (!writer_) throw Error("the writer is closed");
        if (w.size() != 4) throw Error("window: expected (col0, row0, col1, row1)");
        py::gil_scoped_release release;
        call_->named([&] { writer_->write({w[0], w[1], w[2], w[3]}, pointers(parts)); }, outputKeyword_);
    }
    std::vector<std::string> commit() {
        if (!writer_) throw Error("the writer is closed");
        {
            py::gil_scoped_release release;
            call_->named([&] { writer_->commit(); }, outputKeyword_);
            writer_.reset();
        }
        std::vector<std::string> paths;
        for (const auto& t : targets_) paths.push_back(t.out.path);
        return paths;
    }
    void abandon() { writer_.reset(); }

private:
    std::shared_ptr<PyCall> call_;
    std::string outputKeyword_;
    RunContext ctx_;
    RasterRun run_;
    std::vector<RasterTarget> targets_;
    std::unique_ptr<TiledWriter> writer_;
};

// ---- The commands' declarations, for the Python signatures and docstrings -----------------

/// The declarations of the raster commands and sunpos as JSON (demlight::declarationsJson).
std::string optionsJson() {
    std::vector<std::unique_ptr<RasterCommand>> commands;
    std::vector<const ParameterSet*> sets;
    for (const std::string& name : rasterCommandNames()) {
        commands.push_back(makeRasterCommand(name));
        sets.push_back(&commands.back()->declaration());
    }
    const SunposCommand sunpos;
    sets.push_back(&sunpos.declaration());
    return declarationsJson(sets);
}

/// sunpos's report for these keywords, as JSON.
std::string sunposKeywordsJson(const Keywords& keywords) {
    SunposCommand c;
    try {
        for (const auto& [keyword, values] : keywords) c.declaration().set(keyword, values, kPython);
        c.declaration().checkRequired(kPython);
        return demlight::sunposJson(sunposReport(c.values));
    } catch (const Error& e) {
        throw keywordError(e, &c.declaration());
    }
}

/// The reference horizon profile at one point of the DEM: `directions` azimuths evenly spaced
/// from true north, clockwise; (azimuths, elevations) in degrees as float64 arrays, the azimuths
/// true (from north) or, with `fromSouth`, counted from south as PVGIS counts them.
py::tuple horizonProfile(const PyDem& d, double first, double second, bool wgs84, std::size_t directions,
                         std::optional<double> maxDistanceM, double refraction, bool fromSouth) {
    PointHorizon h;
    {
        py::gil_scoped_release release;
        SearchRequest search;
        search.maxDistanceM = maxDistanceM;
        search.refraction = refraction;
        const PointCell cell = locatePoint(*d.source, PointSpec{first, second, wgs84});
        h = pointHorizon(*d.source, cell, evenAzimuthsDeg(directions), search);
    }
    py::array_t<double> azimuths(static_cast<py::ssize_t>(h.samples.size()));
    py::array_t<double> elevations(static_cast<py::ssize_t>(h.samples.size()));
    for (std::size_t i = 0; i < h.samples.size(); ++i) {
        azimuths.mutable_at(static_cast<py::ssize_t>(i)) =
            fromSouth ? southBasedAzimuthDeg(h.azimuthsDeg[i]) : h.azimuthsDeg[i];
        elevations.mutable_at(static_cast<py::ssize_t>(i)) = h.samples[i].angleDeg;
    }
    return py::make_tuple(azimuths, elevations);
}

}  // namespace
}  // namespace demlight::python

PYBIND11_MODULE(_demlight, m) {
    using namespace demlight;
    using namespace demlight::python;
    m.doc() = "demlight's C++ library (the package demlight wraps it; see docs/python.md)";
    m.attr("version") = DEMLIGHT_VERSION;

    static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
    static py::exception<Cancelled> cancelled(m, "Cancelled", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Cancelled& e) {
            cancelled(e.what());
        } catch (const Error& e) {
            error(describeError(e, nullptr, Naming::Python).c_str());
        }
    });

    py::class_<PyDem>(m, "Dem")
        .def_property_readonly("width", [](const PyDem& d) { return d.source->width(); })
        .def_property_readonly("height", [](const PyDem& d) { return d.source->height(); })
        .def_property_readonly("path", [](const PyDem& d) { return d.path; })
        .def_property_readonly("name", [](const PyDem& d) { return d.source->path(); })
        .def_property_readonly("transform", [](const PyDem& d) { return transformTuple(d.geometry().band.ref); })
        .def_property_readonly("crs", [](const PyDem& d) { return d.geometry().band.ref.crsWkt; })
        .def_property_readonly("nodata", [](const PyDem& d) { return d.geometry().band.nodata; })
        .def_property_readonly("epsg", [](const PyDem& d) { return d.geometry().crs.epsg; })
        .def("heights",
             [](const PyDem& d) {
                 if (!d.whole) {
                     std::shared_ptr<const Dem> whole;
                     {
                         py::gil_scoped_release release;
                         whole = d.source->readWhole();
                     }
                     if (!d.whole) d.whole = std::move(whole);  // with the GIL: one thread sets it
                 }
                 return view(d.whole->terrain.heightsM, d.whole);
             })
        .def("info_json", [](const PyDem& d) { return infoJson(d.path.empty() ? d.source->path() : d.path, *d.source); });

    m.def("horizon_profile", &horizonProfile, py::arg("dem"), py::arg("first"), py::arg("second"), py::arg("wgs84"),
          py::arg("directions"), py::arg("max_distance"), py::arg("refraction"), py::arg("from_south"));
    m.def("open", &openPath, py::arg("path"), py::arg("z_unit"), py::arg("z_factor"), py::arg("progress"));
    m.def("from_array", &fromArray, py::arg("heights"), py::arg("transform"), py::arg("crs"), py::arg("nodata"),
          py::arg("name"), py::arg("z_unit"), py::arg("z_factor"));

    py::class_<Raster, std::shared_ptr<Raster>>(m, "Raster")
        .def_property_readonly("bands", [](const std::shared_ptr<Raster>& r) { return rasterBands(r); })
        .def_property_readonly("units",
                               [](const Raster& r) {
                                   py::dict d;
                                   for (const auto& b : r.bands) d[py::str(b.name)] = b.unit;
                                   return d;
                               })
        .def_property_readonly("metadata", [](const Raster& r) { return r.metadata; })
        .def_property_readonly("transform", [](const Raster& r) { return transformTuple(r.ref); })
        .def_property_readonly("crs", [](const Raster& r) { return r.ref.crsWkt; })
        .def_property_readonly("nodata", [](const Raster& r) { return r.flagNodata.value_or(r.nodata); })
        .def(py::pickle([](const Raster& r) { return rasterState(r); },
                        [](const py::tuple& t) { return rasterFromState(t); }));

    py::class_<PyCall, std::shared_ptr<PyCall>>(m, "Call")
        .def_property_readonly("command", [](const PyCall& c) { return c.work.command; })
        .def_property_readonly("z_unit", [](const PyCall& c) { return c.work.heights.zUnit; })
        .def_property_readonly("z_factor", [](const PyCall& c) { return c.work.heights.zFactor; })
        .def("halo", &PyCall::halo, py::arg("dem"))
        .def("extent",
             [](const PyCall& c, const PyDem& dem) {
                 const CellWindow e = c.plan(dem).extent;
                 return py::make_tuple(e.col0, e.row0, e.col1, e.row1);
             })
        .def("compute", &computeCall, py::arg("dem"), py::arg("progress"))
        .def("compute_window", &computeWindow, py::arg("dem"), py::arg("window"), py::arg("progress"))
        .def("write", &writeCall, py::arg("parts"), py::arg("path"), py::arg("format"), py::arg("creation_options"),
             py::arg("command_line"), py::arg("input_path"));

    py::class_<PyWriter>(m, "Writer")
        .def(py::init<std::shared_ptr<PyCall>, const PyDem&, const std::string&, const std::string&,
                      const std::vector<std::string>&, const std::string&, std::string>(),
             py::arg("call"), py::arg("dem"), py::arg("path"), py::arg("format"), py::arg("creation_options"),
             py::arg("command_line"), py::arg("output_keyword") = "path")
        .def("write", &PyWriter::write, py::arg("window"), py::arg("parts"))
        .def("commit", &PyWriter::commit)
        .def("abandon", &PyWriter::abandon);

    m.def("parse", &parseCall, py::arg("command"), py::arg("keywords"));
    m.def("options_json", &optionsJson);
    m.def("sunpos_json", &sunposKeywordsJson, py::arg("keywords"));
    m.def("raster_commands", &rasterCommandNames);
    m.def("tiles", [](const std::vector<std::size_t>& extent, std::size_t cells) {
        const std::vector<CellWindow> tiles = tilesOf({extent.at(0), extent.at(1), extent.at(2), extent.at(3)}, cells);
        py::list out;
        for (const CellWindow& t : tiles) out.append(py::make_tuple(t.col0, t.row0, t.col1, t.row1));
        return out;
    });
}
