// demlight bench DEM -o DIR [--crop N] [--peers]: speed against accuracy of the horizon methods
// on the user's DEM (products/bench.h), written as DIR/bench.csv and a chart (DIR/bench.png and
// DIR/bench.svg, drawn by gnuplot when it is installed). With --peers, GRASS r.horizon runs on
// the same crop, directions and distance, and is scored against the same reference.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "products/bench.h"
#include "products/horizon.h"
#include "src/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
    DemOptions dem;
    std::string outDir;
    std::size_t crop = 400;
    std::size_t sample = 300;
    std::vector<std::size_t> directions = {4, 16, 32};
    std::size_t peerDirections = 16;
    int repeats = 3;
    bool peers = false;
    SearchOptions search;
};

/// The chart (gnuplot): median error against time per cell and direction, log-log, one colour
/// per method family, the Pareto front joined, peers as large squares, the reference (error 0)
/// at the floor, each point labelled with its method and directions.
constexpr const char* kChartScript = R"gp(# Drawn by demlight bench from bench.csv; rerun: gnuplot -e "csv='bench.csv'; out='bench.png'; term='png'" bench.gnuplot
floor = 1e-3
if (!exists("name")) name = csv
set datafile separator comma
if (term eq 'svg') { set terminal svg size 1100,700 font "DejaVu Sans,12" } else { set terminal pngcairo size 1100,700 font "DejaVu Sans,11" }
set output out
set title sprintf("%s: horizon error against time (error 0 drawn at %g deg)", name, floor) noenhanced
set logscale xy
set xlabel "time per cell and direction (ns, whole crop)"
set ylabel "median |horizon - reference| (deg)"
set grid xtics ytics mxtics mytics lc rgb "#e0e0e0"
set key outside right top
stats csv skip 1 using 5 nooutput
set xrange [STATS_min / 2 : STATS_max * 3]
stats csv skip 1 using ($6 > floor ? $6 : floor) nooutput
set yrange [STATS_min / 2 : STATS_max * 3]
e(x) = x > floor ? x : floor
fam(f) = strcol(1) eq f ? e($6) : NaN
front = "< awk -F, 'NR > 1 && $9 == 1' " . csv . " | sort -t, -k5,5g"
lab = 'sprintf("%s N=%d", strcol(2), $3)'
plot front using 5:(e($6)) with lines lw 2 lc rgb "#d62728" title "Pareto front", \
     csv skip 1 using 5:(fam("sweep")) with points pt 7 ps 1.4 lc rgb "#1f77b4" title "demlight sweep", \
     '' skip 1 using 5:(fam("reference")) with points pt 9 ps 1.8 lc rgb "#2ca02c" title "demlight reference (sample)", \
     '' skip 1 using 5:(strcol(1) ne "sweep" && strcol(1) ne "reference" ? e($6) : NaN) with points pt 5 ps 2 lc rgb "#ff7f0e" title "peers", \
     '' skip 1 using 5:(e($6)):(@lab) with labels left offset 1,0.6 font ",9" noenhanced notitle
)gp";

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

bool onPath(const std::string& tool) {
    return std::system(("command -v " + tool + " >/dev/null 2>&1").c_str()) == 0;
}

/// GRASS r.horizon on the crop (written to DIR/peers/crop.tif): `directions` azimuths, the
/// scene's search distance; its module time alone, then each map exported and sampled at the
/// scene's cells. Empty when GRASS is missing or fails (the note says why).
///
/// r.horizon's raster mode names each map basename_ANGLE with ANGLE counterclockwise from east
/// (000 = east, 090 = north), the decimal point as '_', with or without its -c flag (checked with
/// GRASS 8.2: -c does not rename the maps); its directions are true directions (it corrects for
/// the projection, as demlight's azimuths do). So a map's compass azimuth is 90 - ANGLE. Its
/// maxdistance is in metres on any grid (its manual).
std::optional<BenchRow> grassRow(const BenchScene& scene, std::size_t directions, const fs::path& dir, std::string& why) {
    if (!onPath("grass")) {
        why = "GRASS (grass) is not installed; Debian: apt-get install grass-core";
        return std::nullopt;
    }
    const fs::path peers = dir / "peers";
    fs::create_directories(peers);
    const fs::path crop = peers / "crop.tif";
    WriteOptions w;
    w.nodata = -32768;
    writeRaster(crop.string(), {{&scene.crop.terrain.heightsM, nullptr, "height", "m"}}, scene.crop.band.ref, w);
    const Terrain& t = scene.crop.terrain;
    const double distance = std::isfinite(scene.maxDistanceM) ? scene.maxDistanceM : 1e9;
    const fs::path timeFile = peers / "grass_seconds.txt";
    const double stepDeg = 360.0 / static_cast<double>(directions);
    const std::string script =
        "set -e; r.external input=" + shellQuote(crop.string()) + " output=dem --quiet --overwrite; g.region raster=dem; "
        "s=$(date +%s.%N); r.horizon -d elevation=dem step=" + formatNumber(stepDeg) +
        " maxdistance=" + formatNumber(distance) + " output=hor --quiet --overwrite; e=$(date +%s.%N); "
        "awk -v s=\"$s\" -v e=\"$e\" 'BEGIN { printf \"%.6f\\n\", e - s }' > " + shellQuote(timeFile.string()) + "; "
        "for m in $(g.list type=raster pattern='hor_*'); do r.out.gdal input=$m output=" + shellQuote(peers.string()) +
        "/$m.tif format=GTiff type=Float32 --quiet --overwrite -c; done";
    const std::string command = "grass --tmp-location " + shellQuote(crop.string()) + " --exec bash -c " + shellQuote(script) +
                                " > " + shellQuote((peers / "grass_log.txt").string()) + " 2>&1";
    if (std::system(command.c_str()) != 0) {
        why = "GRASS r.horizon failed (its log: " + (peers / "grass_log.txt").string() + ")";
        return std::nullopt;
    }
    BenchRow row;
    row.family = "GRASS r.horizon";
    row.method = "r.horizon";
    std::ifstream(timeFile) >> row.seconds;
    if (!(row.seconds > 0)) {
        why = "GRASS r.horizon: no module time in " + timeFile.string();
        return std::nullopt;
    }
    // Each map at its place among the even compass azimuths (k * step from north, clockwise).
    std::vector<fs::path> maps(directions);
    std::size_t found = 0;
    for (const auto& entry : fs::directory_iterator(peers)) {
        const std::string stem = entry.path().stem().string();
        if (!stem.starts_with("hor_") || entry.path().extension() != ".tif") continue;
        std::string number = stem.substr(4);
        std::replace(number.begin(), number.end(), '_', '.');
        const double compass = std::fmod(450.0 - std::stod(number), 360.0);
        const double k = std::round(compass / stepDeg);
        const auto index = static_cast<std::size_t>(k) % directions;
        if (std::abs(compass - k * stepDeg) > 1e-3 || !maps[index].empty()) {
            why = "GRASS r.horizon wrote an unexpected map " + stem;
            return std::nullopt;
        }
        maps[index] = entry.path();
        ++found;
    }
    if (found != directions) {
        why = "GRASS r.horizon wrote " + std::to_string(found) + " maps for " + std::to_string(directions) + " directions";
        return std::nullopt;
    }
    std::vector<std::vector<float>> atSample;
    for (const fs::path& path : maps) {
        const RasterBand band = readRasterBand(path.string());
        std::vector<float> v;
        for (const CellIndex& c : scene.sample) v.push_back(band.values(c.col, c.row));
        atSample.push_back(std::move(v));
    }
    scoreHorizons(scene, directions, atSample, row);
    const double cells = static_cast<double>(t.width() * t.height());
    row.nsPerCellPerDirection = row.seconds / cells / static_cast<double>(directions) * 1e9;
    row.notes = "module time of r.horizon alone (one process, all directions)";
    return row;
}

void runBench(const BenchOptions& o, const CliContext& ctx) {
    if (o.outDir.empty()) throw Error("give the output folder with -o DIR");
    const fs::path dir(o.outDir);
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error("-o " + o.outDir + ": not a folder");
    fs::create_directories(dir, ec);
    if (ec) throw Error("-o " + o.outDir + ": cannot create the folder (" + ec.message() + ")");

    BenchRequest request;
    request.cropCells = o.crop;
    request.sampleCells = o.sample;
    request.directions = o.directions;
    // The peers are scored at their own azimuths: the sweeps run that count too.
    if (o.peers && std::find(request.directions.begin(), request.directions.end(), o.peerDirections) == request.directions.end())
        request.directions.push_back(o.peerDirections);
    request.repeats = o.repeats;
    request.search = o.search.request;
    const DemSource dem = openDem(o.dem, ctx);
    ProgressBar bar(!ctx.quiet);
    BenchResult result = benchProduct(dem, request, bar.callback());
    bar.finish();

    std::vector<std::string> notes;
    if (o.peers) {
        std::string why;
        if (auto row = grassRow(result.scene, o.peerDirections, dir, why)) result.rows.push_back(*row);
        else notes.push_back(why);
        notes.push_back("SAGA has no horizon-angle tool to score here (its sky-view factor is compared in docs/compare/saga.md)");
    }
    markPareto(result.rows);
    const fs::path csv = dir / "bench.csv";
    std::ofstream(csv) << benchCsv(result.rows);
    std::ofstream(dir / "bench.gnuplot") << kChartScript;

    std::string chart = "no chart: gnuplot is not installed";
    if (onPath("gnuplot")) {
        const std::string name = fs::path(o.dem.path).stem().string() + " " + std::to_string(result.scene.crop.terrain.width()) +
                                 "x" + std::to_string(result.scene.crop.terrain.height());
        bool drawn = true;
        for (const std::string term : {"png", "svg"}) {
            const std::string cmd = "cd " + shellQuote(dir.string()) + " && gnuplot -e " +
                                    shellQuote("csv='bench.csv'; out='bench." + term + "'; term='" + term + "'; name='" + name + "'") +
                                    " bench.gnuplot 2>/dev/null";
            drawn = drawn && std::system(cmd.c_str()) == 0;
        }
        chart = drawn ? (dir / "bench.png").string() + " and bench.svg" : "gnuplot failed to draw the chart";
    }
    for (const BenchRow& r : result.rows)
        std::printf("%-18s %-28s N=%-4zu %10.2f ns/cell/dir  median %.4g deg  p99 %.4g deg%s\n", r.family.c_str(),
                    r.method.c_str(), r.directions, r.nsPerCellPerDirection, r.medianErrorDeg, r.p99ErrorDeg,
                    r.pareto ? "  (Pareto)" : "");
    for (const std::string& n : notes) note(ctx, n);
    note(ctx, "wrote " + csv.string() + " (" + std::to_string(result.rows.size()) + " rows; " +
                  std::to_string(result.scene.sample.size()) + " sampled cells, search distance " +
                  formatDistance(result.scene.maxDistanceM) + "); " + chart);
}

}  // namespace

void registerBench(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand("bench", "Speed against accuracy of the horizon methods on your DEM (CSV and chart)");
    ctx.outputs[cmd->get_name()].kind = "folder";
    addDemArgument(cmd, o->dem);
    cmd->add_option("-o,--output", o->outDir, "Output folder: bench.csv, bench.gnuplot, bench.png, bench.svg")
        ->required()
        ->type_name("DIR");
    cmd->add_option("--crop", o->crop, "Cells a side of the centred crop measured (0 = the whole DEM)")
        ->check(finiteRange(0, 1e6))
        ->capture_default_str();
    cmd->add_option("--sample", o->sample, "Cells scored against the reference ray march")
        ->check(finiteRange(1, 1e6))
        ->capture_default_str();
    cmd->add_option("--directions", o->directions, "Direction counts timed for each sweep method")
        ->check(finiteRange(1, 4096))
        ->expected(1, -1)
        ->capture_default_str();
    cmd->add_option("--repeats", o->repeats, "Timed runs of each method (the median counts)")
        ->check(finiteRange(1, 100))
        ->capture_default_str();
    cmd->add_flag("--peers", o->peers, "Also time and score GRASS r.horizon on the same crop, directions and distance");
    cmd->add_option("--peer-directions", o->peerDirections, "Directions of the peers' run (a multiple of 4)")
        ->check(finiteRange(4, 360))
        // r.horizon's directions run counterclockwise from east: they are the even compass
        // azimuths of the sweeps only when north is one of them.
        ->check(CLI::Validator(
            [](const std::string& s) {
                return s.find_first_not_of("0123456789") == std::string::npos && std::stoul(s) % 4 == 0
                           ? std::string()
                           : "must be a multiple of 4";
            },
            "multiple of 4"))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    o->search.request.threads = 1;  // one core by default: comparable with r.horizon's one
    cmd->callback([o, &ctx] { runBench(*o, ctx); });
}

}  // namespace demlight::cli
