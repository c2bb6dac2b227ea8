// The runner (demlight/run/): a run's tiles are planned with the halo the product itself reads.
#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/products/sun.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/tiles.h"
#include "demlight/run/raster_commands.h"
#include "demlight/run/runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace demlight {
namespace {

/// A 2000 x 2000 DEM of 20 m cells in UTM zone 10N (46 N, from 123 W eastwards) with one 200 m
/// hill: a search of relief / tan(2 deg) (5.7 km, 287 cells) reaches much less than across it, so
/// how far the halo reaches decides the tiles.
DemSource hillDem() {
    constexpr std::size_t n = 2000;
    Grid<float> heights(n, n);
    for (std::size_t r = 0; r < n; ++r)
        for (std::size_t c = 0; c < n; ++c) {
            const double dx = (static_cast<double>(c) - 1000.0) / 75.0, dy = (static_cast<double>(r) - 1000.0) / 75.0;
            heights(c, r) = static_cast<float>(200.0 * std::exp(-(dx * dx + dy * dy)));
        }
    GeoReference ref;
    ref.geoTransform = {500000.0, 20.0, 0.0, 5100000.0, 0.0, -20.0};
    ref.crsWkt = "EPSG:32610";
    return DemSource(demFromArray(heights, ref, std::nullopt, "hill", HeightOptions{}));
}

/// The memory (bytes) the largest tile of `run` holds when it reads `halo` cells around it.
double largestTileBytes(const RasterRun& run, const DemSource& dem, std::size_t halo, const TileBytes& bytes) {
    TileShape largest;
    for (const CellWindow& t : run.tiles) {
        largest.cols = std::max(largest.cols, t.col1 - t.col0);
        largest.rows = std::max(largest.rows, t.row1 - t.row0);
    }
    return tileBytes(largest, halo, dem.width(), dem.height(), bytes);
}

/// A sun below 2 degrees casts shadows longer than the search the scene plan sizes for relief
/// (relief / tan 2 deg): the product reads the longer halo, and the tiles must fit the memory
/// limit with it.
TEST(Runner, LowSunTilesAreSizedForTheSunsHalo) {
    const DemSource dem = hillDem();
    SunParameters p;
    p.time = "2024-06-21T12:33:00Z";  // 1 to 1.5 deg above the horizon on this DEM
    const SunRequest request = sunRequest(p);
    const Terrain& terrain = dem.geometry().terrain;
    const ScenePlan plan = planFor(request.search, terrain);
    const SunField field = sunFieldFor(dem, request.time.utc, request.atmosphere, plan);
    ASSERT_GT(field.elevationRange().first, 0.0);
    ASSERT_LT(field.elevationRange().second, 2.0);

    const std::size_t sunHalo = sunHaloCells(dem, request);
    const std::size_t planHalo = haloCellsFor(terrain, plan.maxDistanceM);
    EXPECT_GT(sunHalo, planHalo + planHalo / 2);  // the case worth the test: a much longer halo

    ProductWork<SunResult> work = sunWork(request, p);
    EXPECT_EQ(work.halo(dem), sunHalo);
    // A memory limit that holds tiles of 300 x 300 cells with the sun's halo, not the whole DEM.
    work.tiling.memoryLimitMB =
        memoryBudgetFor(tileBytes({300, 300}, sunHalo, dem.width(), dem.height(), work.tileBytes)) / 1e6;
    const RasterRun run = work.plan(dem, RunContext{});
    EXPECT_EQ(run.haloCells, sunHalo);
    ASSERT_GT(run.tiles.size(), 1u) << "halo " << sunHalo << " cells";
    const double budget = tileMemoryBytes(work.tiling.memoryLimitMB * 1e6);
    EXPECT_LE(largestTileBytes(run, dem, sunHalo, work.tileBytes), budget);

    // Tiles sized for the plan's halo instead do not fit once the sun's halo is read around them.
    const TilePlan planTiles =
        automaticTiles(dem.whole(), dem.width(), dem.height(), planHalo, work.tileBytes, budget);
    EXPECT_GT(tileBytes(planTiles.shape, sunHalo, dem.width(), dem.height(), work.tileBytes), budget);
}

/// Sun hours integrate suns down to the horizon: their halo is a sun at 0 deg's, and the tiles
/// are planned with it.
TEST(Runner, SunhoursTilesAreSizedForTheHorizonSunsHalo) {
    const DemSource dem = hillDem();
    SunhoursParameters p;
    p.days.date = "2024-06-21";
    p.days.tz = "UTC";
    p.step = "1h";
    const SunhoursRequest request = sunhoursRequest(p);
    const Terrain& terrain = dem.geometry().terrain;
    const std::size_t halo = sunhoursHaloCells(dem, request);
    EXPECT_GT(halo, haloCellsFor(terrain, planFor(request.search, terrain).maxDistanceM));
    ProductWork<SunhoursResult> work = sunhoursWork(request, p);
    work.tiling.memoryLimitMB =
        memoryBudgetFor(tileBytes({600, 600}, halo, dem.width(), dem.height(), work.tileBytes)) / 1e6;
    const RasterRun run = work.plan(dem, RunContext{});
    EXPECT_EQ(run.haloCells, halo);
    EXPECT_LE(largestTileBytes(run, dem, halo, work.tileBytes), tileMemoryBytes(work.tiling.memoryLimitMB * 1e6));
}

/// A search distance given caps every product's halo alike, and the planner uses it.
TEST(Runner, GivenSearchDistanceIsTheHalo) {
    const DemSource dem = hillDem();
    SunParameters p;
    p.time = "2024-06-21T12:32:00Z";
    p.search.maxDistanceM = 1000;
    const ProductWork<SunResult> work = sunWork(p);
    EXPECT_EQ(work.halo(dem), haloCellsFor(dem.geometry().terrain, 1000));
    EXPECT_EQ(work.plan(dem, RunContext{}).haloCells, work.halo(dem));
}

}  // namespace
}  // namespace demlight
