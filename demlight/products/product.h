// What every product shares: the result (named bands plus metadata on the window's
// georeference), the search request of horizon-based products and the scene plan made from it,
// the metadata keys common to all products, and the one loader of auxiliary rasters.
//
// A product is one call: product(source, window, request, progress) -> result. It sizes and
// advances its own progress, never prints, and names request fields (not CLI flags) in its
// errors. Each product also states its halo: the cells around a window whose terrain can change
// the window's answer (its search distance in cells).
#pragma once

#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/core/progress.h"

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// One output band: Float32 values (NaN = nodata) or, when `flags` is set, Byte values.
struct ProductBand {
    std::string name;         ///< band description, e.g. "sun_visibility"
    std::string unit;         ///< what the values are, with their unit
    Grid<float> values;
    Grid<std::uint8_t> flags;  ///< Byte bands (masks); used when values is empty
    /// How coarser versions (COG overviews) are made from the band: Average for quantities
    /// (fractions, irradiance, angles, lengths), Nearest for flags and for bands with marker
    /// values, which a mean would blend into numbers that mean nothing.
    Resampling resampling = Resampling::Average;
};

/// The bands in this order, moved in: a braced list would copy every grid (the elements of an
/// initializer_list are const), doubling a tile's output memory while both exist.
template <class... Bands>
std::vector<ProductBand> movedBands(Bands&&... bands) {
    std::vector<ProductBand> out;
    out.reserve(sizeof...(bands));
    (out.push_back(std::forward<Bands>(bands)), ...);
    return out;
}

/// Named bands on a georeference, plus the dataset metadata (DEMLIGHT_* keys) to write with them.
struct ProductResult {
    std::vector<ProductBand> bands;
    std::map<std::string, std::string> metadata;
    GeoReference ref;  ///< of the window the bands cover
    /// Written for NaN cells of Float32 bands (outputNodata of the DEM).
    double nodata = 0;
    /// Byte bands: their declared nodata value (255 at DEM voids for masks), or none.
    std::optional<double> flagNodata;

    const ProductBand& band(const std::string& name) const;
};

/// Search and modelling options of every product that computes horizons.
struct SearchRequest {
    /// Horizon search distance (metres); none = the scene plan's.
    std::optional<double> maxDistanceM;
    /// Refraction coefficient k of terrain sight lines (effective radius R / (1 - k)).
    double refraction = kDefaultRefraction;
    /// Worker threads (0 = all cores); results are the same bits for any count.
    int threads = 0;
    Quality quality = Quality::Auto;
    /// Horizon error budget of Quality::Auto (degrees).
    double toleranceDeg = kDefaultToleranceDeg;
    /// Near field of the sweeps (HorizonParams::nearFieldSteps, 0 to kMaxNearFieldSteps); none =
    /// the scene plan's.
    std::optional<int> nearFieldSteps;
};

/// The scene plan (demlight/lighting/quality.h) of a request on a terrain; the request's maxDistanceM
/// takes precedence over the plan's distance. Throws Error naming the field on bad values.
ScenePlan planFor(const SearchRequest& search, const Terrain& terrain);

/// HorizonParams of the plan's horizon maps and sun sweeps (planHorizonParams).
HorizonParams horizonParams(const SearchRequest& search, const ScenePlan& plan);
/// HorizonParams of a sky or aperture integral over `directions` sectors (planIntegralParams).
HorizonParams integralParams(const SearchRequest& search, const ScenePlan& plan, const Terrain& terrain,
                             std::size_t directions);
/// HorizonParams of a stack of horizon maps that serves every sun of a sequence (the
/// `interpolated:N` horizon mode): the plan's horizon parameters, two scan lines per cell, out to
/// the lowest sun's shadows (auto: sunSearchDistanceM at 0 deg), the plan's distance (full) or
/// the request's maxDistanceM.
HorizonParams stackHorizonParams(const SearchRequest& search, const ScenePlan& plan, const Terrain& terrain,
                                 double sunDiameterDeg);
/// SunFrameParams of the plan: the request's maxDistanceM when given; with Quality::Full the
/// plan's (the DEM diagonal); with Auto 0, the distance each sun needs (sunSearchDistanceM).
SunFrameParams sunFrameParams(const SearchRequest& search, double sunDiameterDeg, const ScenePlan& plan);
/// The search distance (metres) computeSunFrame takes with sunFrameParams for the sun `field` on
/// `terrain`: the longest any sun of the instant needs, so the halo of a window's sun terms.
double sunFrameDistanceM(const SearchRequest& search, double sunDiameterDeg, const ScenePlan& plan,
                         const Terrain& terrain, const SunField& field);

/// Sky light K (Lambert-weighted visible sky in the normal hemisphere) from `directions` evenly
/// spaced sweeps with `params`; NaN at nodata. The sky fill of pictures and time-lapses.
Grid<float> skyLightK(const Terrain& terrain, const Normals& normals, std::size_t directions,
                      const HorizonParams& params, ProgressCounter* progress);

/// Cells of search distance around a window: ceil(distance / smallest cell side) + 1; the
/// larger DEM side for an infinite distance.
std::size_t haloCellsFor(const Terrain& terrain, double maxDistanceM);

// ---- Metadata --------------------------------------------------------------------------------

/// Shortest decimal form of a number for metadata and band names ("37.5", "0.13").
std::string formatNumber(double value);
/// A search distance for metadata, always a number (metres): the DEM diagonal for an infinite
/// distance, which is the same search.
std::string metadataDistanceM(const Terrain& terrain, double metres);
/// DEMLIGHT_QUALITY, DEMLIGHT_PLAN (choices and reasons), DEMLIGHT_CURVATURE and
/// DEMLIGHT_EXPECTED_ERROR_DEG of a plan.
std::map<std::string, std::string> planMetadata(const ScenePlan& plan);
/// The keys every product writes: DEMLIGHT_VERSION, DEMLIGHT_INPUT, DEMLIGHT_PRODUCT.
std::map<std::string, std::string> productMetadata(const Dem& dem, const std::string& product);
/// DEMLIGHT_MAX_DISTANCE_M and DEMLIGHT_REFRACTION of a search.
std::map<std::string, std::string> searchMetadata(const Terrain& terrain, double maxDistanceM, double refraction);

/// The nodata value written for nodata cells of Float32 outputs: the input's own value when it
/// cannot be mistaken for a result (NaN, or magnitude >= 10000, e.g. -32768, 65535, -3.4e38),
/// otherwise NaN (an input nodata of 0 would collide with a visibility of 0).
double outputNodata(const Dem& dem);

/// An empty result on the DEM's georeference and nodata, with productMetadata and `extra`.
ProductResult makeResult(const Dem& dem, const std::string& product,
                         const std::map<std::string, std::string>& extra = {});

// ---- Windows ---------------------------------------------------------------------------------

/// Runs `compute` for `window` of the source: on the whole DEM directly, otherwise on the window
/// grown by haloCells (read from the source) with the result cropped back to the window and put
/// on the window's georeference. A window result equals the whole DEM's on those cells where the
/// halo holds every occluder; scan lines and lattices are anchored to the read window, so the
/// bits may differ.
template <class Result>
Result onWindow(const DemSource& source, const CellWindow& window, std::size_t haloCells,
                const std::function<Result(const Dem&)>& compute);

/// As onWindow, for products that compute the window's cells only (the halo is read for its
/// occluders and never computed): compute(dem, cells) gets the DEM read with the halo and the
/// window's cells in its coordinates (all of it for the whole DEM), and returns bands of exactly
/// those cells on the read DEM's georeference, which is moved to the window's. A tile then costs
/// the sweeps' walk over the halo, not a horizon for every halo cell.
template <class Result>
Result onWindowCells(const DemSource& source, const CellWindow& window, std::size_t haloCells,
                     const std::function<Result(const Dem&, const CellWindow&)>& compute);

/// Crops every band of `result` (computed on `read`) to `window`, and moves its georeference.
void cropResult(ProductResult& result, const CellWindow& read, const CellWindow& window);
/// Moves the georeference of `result` from `read`'s corner to `window`'s (bands untouched).
void moveReference(ProductResult& result, const CellWindow& read, const CellWindow& window);
/// `window` in the coordinates of `read`, which contains it.
CellWindow cellsWithin(const CellWindow& read, const CellWindow& window);
/// HorizonParams::window for sweeps that serve `cells` of `terrain` (onWindowCells): none when
/// the cells are all of it.
std::optional<CellWindow> sweepWindowOf(const Terrain& terrain, const CellWindow& cells);

template <class Result>
Result onWindow(const DemSource& source, const CellWindow& window, std::size_t haloCells,
                const std::function<Result(const Dem&)>& compute) {
    source.checkWindow(window);
    if (source.isWhole(window)) return compute(*source.readWhole());
    const CellWindow read = source.withHalo(window, haloCells);
    Result result = compute(source.read(read));
    cropResult(result, read, window);
    return result;
}

template <class Result>
Result onWindowCells(const DemSource& source, const CellWindow& window, std::size_t haloCells,
                     const std::function<Result(const Dem&, const CellWindow&)>& compute) {
    source.checkWindow(window);
    if (source.isWhole(window)) {
        const std::shared_ptr<const Dem> whole = source.readWhole();
        return compute(*whole, CellWindow{0, 0, whole->terrain.width(), whole->terrain.height()});
    }
    const CellWindow read = source.withHalo(window, haloCells);
    Dem dem = source.read(read);
    // The raw band values are not needed past the heights; a tile's memory plan
    // (windowProductTileBytes) counts on their memory being free for the sweeps.
    dem.band.values = Grid<float>();
    Result result = compute(dem, cellsWithin(read, window));
    moveReference(result, read, window);
    return result;
}

// ---- Auxiliary rasters -------------------------------------------------------------------------

/// How colour values of an auxiliary raster are encoded.
enum class ColorEncoding {
    Auto,    ///< Srgb when any value exceeds 1 (an 8-bit picture), else Linear
    Srgb,    ///< display-encoded 0-255 (or 0-1), decoded with gamma 2.2
    Linear,  ///< linear albedo 0-1
};
/// "auto", "srgb" or "linear"; throws Error naming `field` otherwise.
ColorEncoding parseColorEncoding(const std::string& name, const std::string& field);

/// What an auxiliary raster holds and how to check it.
struct AuxiliarySpec {
    std::string field;        ///< request field it comes from, named in errors
    std::size_t bands = 1;    ///< bands taken from the file (1: band 1; 3: R, G, B)
    bool greyToRgb = false;   ///< bands = 3: a one-band file is grey, used for all three
    double minValue = 0, maxValue = 1;  ///< valid range after decoding (NaN = no data passes)
    bool color = false;       ///< values are colour, decoded by `encoding`
    ColorEncoding encoding = ColorEncoding::Linear;
};

/// The one loader of auxiliary rasters (albedo, colour, cloud): resampled bilinearly onto the
/// DEM's grid (NaN where the file has no data), band count, range and coverage checked. Throws
/// Error naming spec.field and the file: unreadable, too few bands, a value outside the range
/// (after decoding colour), or no cell of the DEM covered.
std::vector<Grid<float>> loadAuxiliaryRaster(const std::string& path, const DemSource& source, const AuxiliarySpec& spec);

}  // namespace demlight
