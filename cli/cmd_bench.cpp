// demlight bench DEM -o DIR [--crop N] [--peers]: speed against accuracy of the horizon methods
// on the user's DEM (demlight/products/bench.h), written as DIR/bench.csv and a chart (DIR/bench.png and
// DIR/bench.svg, drawn by gnuplot when it is installed). With --peers, GRASS r.horizon runs on
// the same crop, directions and distance, and is scored against the same reference.
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/progress_bar.h"
#include "demlight/geo/output_file.h"
#include "demlight/products/bench.h"
#include "demlight/products/horizon.h"
#include "demlight/core/error.h"
#include "demlight/core/process.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace demlight::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
    ParameterSet set{"bench", "Speed against accuracy of the horizon methods on your DEM (CSV and chart)"};
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
constexpr const char* kChartScript = R"gp(# Drawn by demlight bench from bench.csv; rerun in this folder: gnuplot -c bench.gnuplot png [TITLE [OUTPUT]]
# Its arguments are data, never code: the terminal (png or svg), the title, the picture's path.
floor = 1e-3
csv = 'bench.csv'
term = ARGC >= 1 ? ARG1 : 'png'
name = ARGC >= 2 ? ARG2 : csv
out = ARGC >= 3 ? ARG3 : 'bench.' . term
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
labels = 'bench_labels.csv'
e(x) = x > floor ? x : floor
fam(f) = strcol(1) eq f ? e($6) : NaN
plot 'bench_front.csv' skip 1 using 5:(e($6)) with lines lw 2 lc rgb "#d62728" title "Pareto front", \
     csv skip 1 using 5:(fam("sweep")) with points pt 7 ps 1.4 lc rgb "#1f77b4" title "demlight sweep", \
     '' skip 1 using 5:(fam("reference")) with points pt 9 ps 1.8 lc rgb "#2ca02c" title "demlight reference (sample)", \
     '' skip 1 using 5:(strcol(1) ne "sweep" && strcol(1) ne "reference" ? e($6) : NaN) with points pt 5 ps 2 lc rgb "#ff7f0e" title "peers", \
     labels skip 1 using 1:2 with lines lw 0.5 lc rgb "#909090" notitle, \
     labels skip 1 using 3:4:5 with labels left font ",9" noenhanced notitle
)gp";

/// The chart's plot area in pixels (1100 x 700 with the key outside on the right, as gnuplot lays
/// it out for kChartScript) and the size of a 9-point label's character.
constexpr double kPlotWidthPx = 670, kPlotHeightPx = 590, kCharWidthPx = 6.6, kLabelHeightPx = 12, kMarkerPx = 9;
constexpr double kErrorFloorDeg = 1e-3;  // the script's floor: error 0 is drawn there

/// Where each row's label goes, so that no two labels overlap and none covers a point: the chart
/// has the script's axes (log-log, from half the smallest to three times the largest value), and
/// each label tries places around its point, nearest first, keeping the first that is free and
/// inside the plot. Written as DIR/bench_labels.csv: the leader line's two ends (the point, then
/// the label's anchor, a blank line between rows) and the label's text at the anchor.
std::string chartLabels(const std::vector<BenchRow>& rows) {
    if (rows.empty()) return "x,y,label_x,label_y,label\n";
    auto shown = [](double err) { return std::max(err, kErrorFloorDeg); };
    double x0 = rows[0].nsPerCellPerDirection, x1 = x0, y0 = shown(rows[0].medianErrorDeg), y1 = y0;
    for (const BenchRow& r : rows) {
        x0 = std::min(x0, r.nsPerCellPerDirection), x1 = std::max(x1, r.nsPerCellPerDirection);
        y0 = std::min(y0, shown(r.medianErrorDeg)), y1 = std::max(y1, shown(r.medianErrorDeg));
    }
    const double lx0 = std::log(x0 / 2), lxs = std::log(x1 * 3) - lx0, ly0 = std::log(y0 / 2), lys = std::log(y1 * 3) - ly0;
    struct Box {
        double left, bottom, right, top;
        bool meets(const Box& b) const { return left < b.right && b.left < right && bottom < b.top && b.bottom < top; }
    };
    std::vector<Box> taken;  // every point's marker, then each placed label
    std::vector<std::pair<double, double>> at;  // each row's point in pixels
    for (const BenchRow& r : rows) {
        const double px = (std::log(r.nsPerCellPerDirection) - lx0) / lxs * kPlotWidthPx;
        const double py = (std::log(shown(r.medianErrorDeg)) - ly0) / lys * kPlotHeightPx;
        at.emplace_back(px, py);
        taken.push_back({px - kMarkerPx, py - kMarkerPx, px + kMarkerPx, py + kMarkerPx});
    }
    std::ostringstream out;
    out.precision(9);
    out << "x,y,label_x,label_y,label\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const BenchRow& r = rows[i];
        const std::string text = r.method + " N=" + std::to_string(r.directions);
        const double w = kCharWidthPx * static_cast<double>(text.size());
        const auto [px, py] = at[i];
        // Anchors (the label's left end, vertically centred): right of the point, then left of it,
        // each at rising distances above and below.
        std::vector<std::pair<double, double>> tries;
        for (double dy : {8.0, -8.0, 22.0, -22.0, 36.0, -36.0, 50.0, -50.0, 64.0, -64.0}) {
            tries.emplace_back(px + 10, py + dy);
            tries.emplace_back(px - 10 - w, py + dy);
        }
        std::pair<double, double> pick = tries.front();
        for (const auto& [ax, ay] : tries) {
            const Box box{ax, ay - kLabelHeightPx / 2, ax + w, ay + kLabelHeightPx / 2};
            if (box.left < 0 || box.right > kPlotWidthPx || box.bottom < 0 || box.top > kPlotHeightPx) continue;
            if (std::none_of(taken.begin(), taken.end(), [&](const Box& b) { return box.meets(b); })) {
                pick = {ax, ay};
                break;
            }
        }
        taken.push_back({pick.first, pick.second - kLabelHeightPx / 2, pick.first + w, pick.second + kLabelHeightPx / 2});
        const double ax = std::exp(lx0 + pick.first / kPlotWidthPx * lxs), ay = std::exp(ly0 + pick.second / kPlotHeightPx * lys);
        // The leader runs from the point to the label's near end.
        const double nearX = pick.first < px ? std::exp(lx0 + (pick.first + w) / kPlotWidthPx * lxs) : ax;
        const double y = shown(r.medianErrorDeg);
        out << r.nsPerCellPerDirection << ',' << y << ',' << ax << ',' << ay << ",\"" << text << "\"\n";
        out << nearX << ',' << ay << ",,,\n\n";
    }
    return out.str();
}

bool onPath(const std::string& tool) { return findProgram(tool).has_value(); }

/// Writes `text` to `path` through a temporary file (an existing name there, link or not, is
/// replaced, never written through); throws Error naming the file when the write fails.
void writeTextFile(const fs::path& path, const std::string& text) {
    TemporaryFile tmp(path.string());
    std::ofstream out(tmp.path(), std::ios::binary);
    out << text;
    out.close();
    if (!out) throw Error(writeFailureMessage("'" + path.string() + "'", tmp.path(), {}));
    tmp.commit();
}

/// Whether `path` holds a whole picture of gnuplot's `term`: a PNG ending with its IEND chunk, an
/// SVG with its closing tag. gnuplot does not always fail when its output is cut short.
bool wholePicture(const fs::path& path, const std::string& term) {
    std::ifstream in(path, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (term == "png") {
        static const std::string kIend("\x00\x00\x00\x00IEND\xae\x42\x60\x82", 12);
        return bytes.size() > 8 + kIend.size() && bytes.compare(0, 4, "\x89PNG") == 0 && bytes.ends_with(kIend);
    }
    const auto close = bytes.rfind("</svg>");
    return close != std::string::npos && bytes.find_first_not_of(" \t\r\n", close + 6) == std::string::npos;
}

/// Draws DIR/bench.TERM with gnuplot (the script and its data files already in `dir`) under a
/// temporary name; an empty string, or why not.
std::string drawChart(const fs::path& dir, const std::string& term, const std::string& title) {
    const fs::path final = dir / ("bench." + term);
    TemporaryFile tmp(final.string());
    const fs::path log = fs::path(tmp.path()).parent_path() / "gnuplot.log";  // removed with the folder
    const ProgramExit run = runProgram({{"gnuplot", "-c", "bench.gnuplot", term, title, tmp.path()}, dir.string(), log.string()});
    if (!run.ok()) {
        std::ifstream in(log);
        std::string line, last;
        while (std::getline(in, line))
            if (!line.empty()) last = line;
        return "gnuplot failed to draw " + final.string() + " (" + run.why + (last.empty() ? "" : ": " + last) + ")";
    }
    if (!wholePicture(tmp.path(), term))
        return writeFailureMessage("'" + final.string() + "'", tmp.path(), "gnuplot's picture is cut short");
    tmp.commit();
    return {};
}

/// The rows on the Pareto front by rising time, as bench.csv rows (the chart joins them).
std::vector<BenchRow> paretoFront(std::vector<BenchRow> rows) {
    std::erase_if(rows, [](const BenchRow& r) { return !r.pareto; });
    std::stable_sort(rows.begin(), rows.end(), [](const BenchRow& a, const BenchRow& b) {
        return a.nsPerCellPerDirection < b.nsPerCellPerDirection;
    });
    return rows;
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
    // The script is a constant: the paths and numbers reach it as its positional arguments
    // ($1 the crop, $2 the peers folder, $3 the time file, $4 the step, $5 the distance).
    const std::string script =
        "set -e; r.external input=\"$1\" output=dem --quiet --overwrite; g.region raster=dem; "
        "s=$(date +%s.%N); r.horizon -d elevation=dem step=\"$4\" maxdistance=\"$5\" output=hor --quiet --overwrite; "
        "e=$(date +%s.%N); awk -v s=\"$s\" -v e=\"$e\" 'BEGIN { printf \"%.6f\\n\", e - s }' > \"$3\"; "
        "for m in $(g.list type=raster pattern='hor_*'); do "
        "r.out.gdal input=\"$m\" output=\"$2/$m.tif\" format=GTiff type=Float32 --quiet --overwrite -c; done";
    const ProgramExit grass = runProgram({{"grass", "--tmp-location", crop.string(), "--exec", "bash", "-c", script, "bash",
                                           crop.string(), peers.string(), timeFile.string(), formatNumber(stepDeg),
                                           formatNumber(distance)},
                                          {},
                                          (peers / "grass_log.txt").string()});
    if (!grass.ok()) {
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
    writeTextFile(csv, benchCsv(result.rows));
    writeTextFile(dir / "bench_front.csv", benchCsv(paretoFront(result.rows)));
    std::string script = kChartScript;
    const bool anyPeer = std::any_of(result.rows.begin(), result.rows.end(), [](const BenchRow& r) {
        return r.family != "sweep" && r.family != "reference";
    });
    if (!anyPeer) {  // no key entry for points the chart does not have
        const std::string peersTitle = "title \"peers\"";
        script.replace(script.find(peersTitle), peersTitle.size(), "notitle");
    }
    writeTextFile(dir / "bench.gnuplot", script);
    writeTextFile(dir / "bench_labels.csv", chartLabels(result.rows));

    std::string chart = "no chart: gnuplot is not installed";
    if (onPath("gnuplot")) {
        const std::string title = fs::path(o.dem.path).stem().string() + " " + std::to_string(result.scene.crop.terrain.width()) +
                                  "x" + std::to_string(result.scene.crop.terrain.height());
        for (const std::string term : {"png", "svg"})
            if (const std::string failed = drawChart(dir, term, title); !failed.empty()) throw Error(failed);
        chart = (dir / "bench.png").string() + " and bench.svg";
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
    ParameterSet& set = o->set;
    declareDemOptions(set, o->dem);
    set.add("output", o->outDir, "Output folder",
            "Output folder: bench.csv, bench.gnuplot, bench_labels.csv, bench.png, bench.svg")
        .flags("-o,--output")
        .type("DIR")
        .mandatory();
    set.add("crop", o->crop, "Crop side (cells)", "Cells a side of the centred crop measured (0 = the whole DEM)")
        .within(0, 1e6);
    set.add("sample", o->sample, "Scored cells", "Cells scored against the reference ray march")
        .within(1, 1e6)
        .field("sampleCells");
    set.add("directions", o->directions, "Direction counts", "Direction counts timed for each sweep method")
        .within(1, 4096)
        .byDefault("4 16 32");
    set.add("repeats", o->repeats, "Timed runs", "Timed runs of each method (the median counts)").within(1, 100);
    set.add("peers", o->peers, "Also run GRASS r.horizon",
            "Also time and score GRASS r.horizon on the same crop, directions and distance");
    set.add("peer_directions", o->peerDirections, "Peer directions", "Directions of the peers' run (a multiple of 4)")
        .within(4, 360)
        // r.horizon's directions run counterclockwise from east: they are the even compass
        // azimuths of the sweeps only when north is one of them.
        .check([](std::string& s) { return std::stoul(s) % 4 == 0 ? std::string() : "must be a multiple of 4"; });
    o->search.request.threads = 1;  // one core by default: comparable with r.horizon's one
    declareSearchOptions(set, o->search);
    commandLineOnly(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    ctx.outputs[cmd->get_name()].kind = "folder";
    cmd->callback([o, &ctx] { runBench(*o, ctx); });
}

}  // namespace demlight::cli
