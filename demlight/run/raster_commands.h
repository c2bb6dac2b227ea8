// The raster commands (horizon, sun, sky, aperture, light, irradiance, insolation, sunhours) as
// works: each command's parameters as a front end sets them, and one function per command that
// builds the product's work (demlight/run/runner.h) from them: xxxWork(parameters), or, for a
// front end that needs the request for its own notes, xxxWork(xxxRequest(parameters), parameters). The command line and the Python
// module both build their runs here, so a command's requests, tiles and outputs are made once.
#pragma once

#include "demlight/products/aperture.h"
#include "demlight/products/canopy.h"
#include "demlight/products/horizon.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/light.h"
#include "demlight/products/sky.h"
#include "demlight/products/sun.h"
#include "demlight/products/sunhours.h"
#include "demlight/run/options.h"
#include "demlight/run/parameters.h"
#include "demlight/run/runner.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// What every raster command takes: how its DEM is opened, how it is tiled, how horizons are
/// searched.
struct RasterParameters {
    HeightOptions heights;
    TilingOptions tiling;
    SearchRequest search;
};

struct HorizonParameters : RasterParameters {
    std::vector<double> azimuthsDeg;
    int directions = 0;
    std::string method = "sweep";
    std::string dataType = "Float32";  ///< Float32, or Int16 (fixed point, horizonFixedPoint)
};
/// The request; `point`: a point query, whose profile defaults to PVGIS's 48 directions.
HorizonRequest horizonRequest(const HorizonParameters& p, bool point = false);
/// The horizons and their truncation mask, written to OUT and OUT.truncated.tif.
ProductWork<HorizonResult> horizonWork(const HorizonRequest& request, const HorizonParameters& p);
ProductWork<HorizonResult> horizonWork(const HorizonParameters& p);
/// The metadata item of both horizon rasters that names the truncation mask's file.
inline constexpr const char* kTruncationMaskKey = "DEMLIGHT_TRUNCATION_MASK";

struct SunParameters : RasterParameters {
    std::string time, tz;
    double sunDiameterDeg = kSunDiameterDeg;
    Atmosphere atmosphere;
    std::string model = "horizon";
    std::optional<std::size_t> directions;
    CanopyRequest canopy;
};
SunRequest sunRequest(const SunParameters& p);
ProductWork<SunResult> sunWork(const SunRequest& request, const SunParameters& p);
ProductWork<SunResult> sunWork(const SunParameters& p);

struct SkyParameters : RasterParameters {
    std::optional<std::size_t> directions;
    double albedo = kDefaultAlbedo;
    std::string albedoRaster;
    std::string patches;
    std::string model = "stewart-langer";
};
SkyRequest skyRequest(const SkyParameters& p);
ProductWork<SkyResult> skyWork(const SkyRequest& request, const SkyParameters& p);
ProductWork<SkyResult> skyWork(const SkyParameters& p);

struct ApertureParameters : RasterParameters {
    std::optional<std::size_t> directions;
};
ApertureRequest apertureRequest(const ApertureParameters& p);
ProductWork<ApertureResult> apertureWork(const ApertureRequest& request, const ApertureParameters& p);
ProductWork<ApertureResult> apertureWork(const ApertureParameters& p);

struct LightParameters : RasterParameters {
    std::string time, tz;
    std::string model = "horizon";
    std::string skyModel = "stewart-langer";
    std::string sunColor, skyColor;
    std::optional<double> albedo;
    std::string albedoRaster, colorRaster, colorEncoding = "auto", cloudShadow;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    CanopyRequest canopy;
};
LightRequest lightRequest(const LightParameters& p);
ProductWork<LightResult> lightWork(const LightRequest& request, const LightParameters& p);
ProductWork<LightResult> lightWork(const LightParameters& p);

struct IrradianceParameters : RasterParameters {
    ClearSkyOptions sky;
    CanopyRequest canopy;
    std::string time, tz;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
};
IrradianceRequest irradianceRequest(const IrradianceParameters& p);
ProductWork<IrradianceResult> irradianceWork(const IrradianceRequest& request, const IrradianceParameters& p);
ProductWork<IrradianceResult> irradianceWork(const IrradianceParameters& p);

struct InsolationParameters : RasterParameters {
    ClearSkyOptions sky;
    CanopyRequest canopy;
    DayOptions days = periodDays();
    std::string step = "10m";
    std::optional<std::size_t> directions;
    double elevationBandDeg = kDefaultInsolationBandDeg;
    double sunDiameterDeg = kSunDiameterDeg;

    static DayOptions periodDays() {
        DayOptions d;
        d.periods = true;
        return d;
    }
};
InsolationRequest insolationRequest(const InsolationParameters& p);
ProductWork<InsolationResult> insolationWork(const InsolationRequest& request, const InsolationParameters& p);
ProductWork<InsolationResult> insolationWork(const InsolationParameters& p);

struct SunhoursParameters : RasterParameters {
    CanopyRequest canopy;
    DayOptions days;
    std::string step = "10m";
    double sunDiameterDeg = kSunDiameterDeg;
    double albedo = kDefaultAlbedo;
    std::optional<std::size_t> skyDirections;
    std::string horizonMode = "auto";
};
SunhoursRequest sunhoursRequest(const SunhoursParameters& p);
ProductWork<SunhoursResult> sunhoursWork(const SunhoursRequest& request, const SunhoursParameters& p);
ProductWork<SunhoursResult> sunhoursWork(const SunhoursParameters& p);

// ---- The raster commands as every front end sees them -------------------------------------

/// A raster command's declaration (demlight/run/parameters.h) and the values set through it: the
/// command line parses into it, Python sets keywords on it, QGIS's form is made from it.
class RasterCommand {
public:
    virtual ~RasterCommand() = default;
    RasterCommand(const RasterCommand&) = delete;
    RasterCommand& operator=(const RasterCommand&) = delete;

    ParameterSet& declaration() { return set_; }
    const ParameterSet& declaration() const { return set_; }
    /// The work of the values set; throws Error (often a ParameterError) on values that do not
    /// go together.
    virtual RasterWork work() const = 0;

    /// The DEM and the output raster: parameters of the command line and QGIS (Python passes the
    /// DEM to the call and the output to Result.write).
    std::string demPath;
    OutputOptions out;
    bool verbose = false;  ///< the command line's scene-plan notes

protected:
    RasterCommand(std::string name, std::string description) : set_(std::move(name), std::move(description)) {}

private:
    ParameterSet set_;
};

/// A raster command whose product's parameters are a P.
template <class P>
class RasterCommandOf final : public RasterCommand {
public:
    using Declare = void (*)(RasterCommandOf&);
    using MakeWork = RasterWork (*)(const P&);
    RasterCommandOf(std::string name, std::string description, Declare declare, MakeWork makeWork)
        : RasterCommand(std::move(name), std::move(description)), makeWork_(makeWork) {
        declare(*this);
    }
    RasterWork work() const override { return makeWork_(values); }

    P values;

private:
    MakeWork makeWork_;
};

std::unique_ptr<RasterCommandOf<HorizonParameters>> horizonCommand();
std::unique_ptr<RasterCommandOf<SunParameters>> sunCommand();
std::unique_ptr<RasterCommandOf<SkyParameters>> skyCommand();
std::unique_ptr<RasterCommandOf<ApertureParameters>> apertureCommand();
std::unique_ptr<RasterCommandOf<LightParameters>> lightCommand();
std::unique_ptr<RasterCommandOf<IrradianceParameters>> irradianceCommand();
std::unique_ptr<RasterCommandOf<InsolationParameters>> insolationCommand();
std::unique_ptr<RasterCommandOf<SunhoursParameters>> sunhoursCommand();

/// The raster commands' names, in the order the command line lists them.
const std::vector<std::string>& rasterCommandNames();
/// A fresh raster command by name (rasterCommandNames); throws Error for another name.
std::unique_ptr<RasterCommand> makeRasterCommand(const std::string& name);

}  // namespace demlight
