#include "demlight/products/point.h"

#include "demlight/geo/solar_position.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>

namespace demlight {
namespace {

constexpr double kWhPerKWh = 1000;

std::string describePoint(const PointSpec& p) {
    return p.wgs84 ? "latitude " + formatNumber(p.first) + ", longitude " + formatNumber(p.second)
                   : "x " + formatNumber(p.first) + ", y " + formatNumber(p.second);
}

/// The window a point query reads: the cell and the search distance around it.
Dem readAround(const DemSource& source, const PointCell& p, std::size_t haloCells, CellIndex& local) {
    const CellWindow cell{p.cell.col, p.cell.row, p.cell.col + 1, p.cell.row + 1};
    const CellWindow w = source.withHalo(cell, haloCells);
    local = {p.cell.col - w.col0, p.cell.row - w.row0};
    return source.read(w);
}

/// The cell's unit normal, from its 3 x 3 neighbourhood (clipped at the DEM edge), as the raster
/// products' normals see it.
Enu normalAt(const DemSource& source, const PointCell& p) {
    CellIndex local;
    const Dem d = readAround(source, p, 1, local);
    return computeNormals(d.terrain).at(local.col, local.row);
}

/// Reference horizons (degrees) of one cell in each azimuth, in parallel over the azimuths.
std::vector<HorizonSample> marchAll(const Terrain& t, CellIndex cell, const HorizonParams& params,
                                    const std::vector<double>& azimuthsDeg) {
    std::vector<HorizonSample> out(azimuthsDeg.size());
    const std::vector<CellIndex> one{cell};
    parallelFor(0, azimuthsDeg.size(), [&](std::size_t i) {
        HorizonParams p = params;
        p.azimuthDeg = azimuthsDeg[i];
        out[i] = referenceHorizonAt(t, p, one).front();
    }, 8);
    return out;
}

/// K0 of the visible-sky model at a cell: sky K of the horizons in D directions raised to the
/// horizontal (demlight/lighting/irradiance.h), the horizons from the ray march.
double skyK0At(const Terrain& t, CellIndex cell, const HorizonParams& params, std::size_t directions,
               const Enu& normal) {
    std::vector<double> azimuths(directions);
    for (std::size_t i = 0; i < directions; ++i) azimuths[i] = directionAzimuthDeg(i, directions);
    const std::vector<HorizonSample> h = marchAll(t, cell, params, azimuths);
    std::vector<float> raised(directions);
    for (std::size_t i = 0; i < directions; ++i) raised[i] = std::max(h[i].angleDeg, 0.0f);
    return skyK(raised, normal);
}

/// The sun at the cell: SPA at its latitude, longitude and height.
SolarPosition sunAt(const PointCell& p, UtcInstant t, const Atmosphere& atmosphere, double* earthSunDistanceAu) {
    SolarSite site;
    site.latitudeDeg = p.latitudeDeg;
    site.longitudeDeg = p.longitudeDeg;
    site.elevationM = p.heightM;
    site.pressureHpa = atmosphere.pressureHpa;
    site.temperatureC = atmosphere.temperatureC;
    SpaTrace trace{};
    const SolarPosition s = solarPosition(site, t, SpaOptions{}, &trace);
    if (earthSunDistanceAu) *earthSunDistanceAu = trace.earthSunDistanceAu;
    return s;
}

/// The cell's view of a sun at (azimuthDeg, elevationDeg) over a horizon of horizonDeg in its azimuth.
CellView viewOf(const Enu& n, double horizonDeg, double azimuthDeg, double elevationDeg, double sunDiameterDeg,
                std::optional<double> skyK0) {
    const SunTerms terms = sunTerms(n, horizonDeg, azimuthDeg, elevationDeg, sunDiameterDeg);
    const double az = azimuthDeg * kDegToRad, el = elevationDeg * kDegToRad;
    const double toward = n.east * std::sin(az) + n.north * std::cos(az);
    CellView view;
    view.sunIrradiance = terms.irradiance;
    view.sunVisibility = terms.visibility;
    view.surface = {n.up, toward, toward * std::cos(el) + n.up * std::sin(el), el};
    if (skyK0) view.skyK0 = *skyK0;
    return view;
}

/// The clear-sky inputs at the point: the constants, or the rasters' values at its cell.
/// `linkeByMonth` receives the twelve values of monthly Linke maps (empty otherwise).
IrradianceParams inputsAt(const DemSource& source, const PointCell& p, const ClearSkyRasters& rasters,
                          IrradianceParams constants, std::vector<double>* linkeByMonth = nullptr) {
    std::vector<double> months;
    const IrradianceParams q = clearSkyAtCell(rasters, source, p.cell, constants, &months);
    if (linkeByMonth) *linkeByMonth = months;
    std::vector<double> values{q.linke, q.albedo, q.coeffBh, q.coeffDh};
    values.insert(values.end(), months.begin(), months.end());
    for (const double v : values)
        if (std::isnan(v))
            throw FieldError("point", " (column " + std::to_string(p.cell.col) + ", row " + std::to_string(p.cell.row) +
                                          "): a clear-sky raster has no data there");
    return q;
}

/// The request's constant clear-sky inputs (an irradiance or an insolation request); rasters,
/// where given, replace them at the cell (inputsAt).
template <class Request>
IrradianceParams constantInputs(const Request& request) {
    IrradianceParams p;
    p.model = request.diffuseModel;
    p.albedo = request.albedo;
    p.coeffBh = request.coeffBh;
    p.coeffDh = request.coeffDh;
    return p;
}

/// Point queries march the one surface: a canopy is for the rasters.
void refuseCanopy(const CanopyRequest& canopy) {
    if (canopy.any())
        throw FieldError("canopy", ": point queries do not model a canopy; compute the raster and read its cell");
}

}  // namespace

PointCell locatePoint(const DemSource& source, const PointSpec& point) {
    const Dem& dem = source.geometry();
    if (!std::isfinite(point.first) || !std::isfinite(point.second))
        throw FieldError("point", " " + describePoint(point) + ": must be finite numbers");
    if (point.wgs84 && !(std::abs(point.first) <= 90 && std::abs(point.second) <= 360))
        throw FieldError("point", " " + describePoint(point) + ": latitude must be in [-90, 90] and longitude in "
                                  "[-360, 360] degrees");
    PointCell p;
    std::tie(p.x, p.y) = point.wgs84 ? crsPointOfWgs84(dem, point.first, point.second)
                                     : std::pair(point.first, point.second);
    const auto& gt = dem.band.ref.geoTransform;
    double col = std::floor((p.x - gt[0]) / gt[1]);
    const double width = static_cast<double>(source.width());
    if (dem.crs.geographic && !(col >= 0 && col < width)) {
        // Longitudes name a meridian modulo 360: a DEM over 179.9..180.1 or 359.9..360.1 holds
        // -179.99 and 0 too. Take the turn nearest the DEM's central meridian.
        const double centre = gt[0] + 0.5 * width * gt[1];
        const double turned = p.x + 360.0 * std::round((centre - p.x) / 360.0);
        const double turnedCol = std::floor((turned - gt[0]) / gt[1]);
        if (turnedCol >= 0 && turnedCol < width) {
            p.x = turned;
            col = turnedCol;
        }
    }
    const double row = std::floor((p.y - gt[3]) / gt[5]);
    if (!(col >= 0 && row >= 0 && col < width && row < static_cast<double>(source.height())))
        throw FieldError("point", " " + describePoint(point) + " (x " + formatNumber(p.x) + ", y " + formatNumber(p.y) +
                                      " in its CRS) is outside the DEM '" + dem.band.path + "'");
    p.cell = {static_cast<std::size_t>(col), static_cast<std::size_t>(row)};
    p.centreX = gt[0] + (col + 0.5) * gt[1];
    p.centreY = gt[3] + (row + 0.5) * gt[5];
    std::tie(p.latitudeDeg, p.longitudeDeg) = cellLatLon(dem, col + 0.5, row + 0.5);
    const float z = source.heightsM({p.cell.col, p.cell.row, p.cell.col + 1, p.cell.row + 1})(0, 0);
    if (std::isnan(z))
        throw FieldError("point", " " + describePoint(point) + " falls on a nodata cell (column " +
                                      std::to_string(p.cell.col) + ", row " + std::to_string(p.cell.row) + ") of '" +
                                      dem.band.path + "'");
    p.heightM = z;
    return p;
}

PointSearch pointSearch(const DemSource& source, const SearchRequest& search) {
    PointSearch s;
    const Terrain& whole = source.geometry().terrain;
    s.plan = planFor(search, whole);
    s.params = horizonParams(search, s.plan);
    s.haloCells = haloCellsFor(whole, s.params.maxDistanceM);
    return s;
}

PointHorizon pointHorizon(const DemSource& source, const PointCell& point, const std::vector<double>& azimuthsDeg,
                          const SearchRequest& search) {
    return withThreads(search.threads, [&] {
        if (azimuthsDeg.empty()) throw FieldError("azimuthsDeg", ": give at least one azimuth");
        const PointSearch s = pointSearch(source, search);
        CellIndex local;
        const Dem d = readAround(source, point, s.haloCells, local);
        PointHorizon out;
        out.point = point;
        out.azimuthsDeg = azimuthsDeg;
        out.samples = marchAll(d.terrain, local, s.params, azimuthsDeg);
        out.maxDistanceM = s.params.maxDistanceM;
        return out;
    });
}

PointIrradiance pointIrradiance(const DemSource& source, const PointCell& point, const IrradianceRequest& request) {
    return withThreads(request.search.threads, [&] {
        validateIrradiance(request);
        refuseCanopy(request.canopy);
        PointIrradiance out;
        out.point = point;
        out.linke = linkeFor(request);
        double distanceAu = 1;
        const SolarPosition sun = sunAt(point, request.time.utc, request.atmosphere, &distanceAu);
        out.sunAzimuthDeg = sun.azimuthDeg;
        out.sunElevationDeg = sun.elevationDeg;
        out.extraterrestrialWm2 = extraterrestrialIrradiance(distanceAu, request.solarConstantWm2);

        const PointSearch s = pointSearch(source, request.search);
        out.maxDistanceM = s.params.maxDistanceM;
        CellIndex local;
        const Dem d = readAround(source, point, s.haloCells, local);
        const Enu n = normalAt(source, point);
        out.horizonAtSunDeg = marchAll(d.terrain, local, s.params, {sun.azimuthDeg}).front().angleDeg;
        if (request.diffuseModel == DiffuseModel::VisibleSky) {
            out.skyDirections = request.skyDirections.value_or(static_cast<std::size_t>(s.plan.skyDirections));
            out.skyK0 = skyK0At(d.terrain, local, s.params, out.skyDirections, n);
        }
        IrradianceParams constants = constantInputs(request);
        constants.linke = out.linke;
        std::vector<double> linkeByMonth;
        const IrradianceParams params = inputsAt(source, point, request.rasters, constants, &linkeByMonth);
        out.linke = linkeByMonth.empty() ? params.linke : linkeByMonth[monthAt(request.time.utc, request.time.zone)];
        const CellView view =
            viewOf(n, out.horizonAtSunDeg, sun.azimuthDeg, sun.elevationDeg, request.sunDiameterDeg, out.skyK0);
        out.sunVisibility = view.sunVisibility;
        const ClearSky sky = clearSky(out.extraterrestrialWm2, out.linke, sun.elevationDeg, point.heightM, params.coeffBh,
                                      params.coeffDh);
        out.irradiance = cellIrradiance(sky, view, params);
        return out;
    });
}

PointInsolation pointInsolation(const DemSource& source, const PointCell& point, const InsolationRequest& request) {
    return withThreads(request.search.threads, [&] {
        validateInsolation(request);
        refuseCanopy(request.canopy);
        PointInsolation out;
        out.point = point;
        std::tie(out.start, out.end) = insolationPeriod(request);
        const std::vector<UtcInstant> times = periodInstants(request);
        out.instants = times.size();

        const PointSearch s = pointSearch(source, request.search);
        out.maxDistanceM = s.params.maxDistanceM;
        CellIndex local;
        const Dem d = readAround(source, point, s.haloCells, local);
        const Enu n = normalAt(source, point);
        if (request.diffuseModel == DiffuseModel::VisibleSky) {
            out.skyDirections = request.directions.value_or(kDefaultInsolationDirections);
            out.skyK0 = skyK0At(d.terrain, local, s.params, out.skyDirections, n);
        }
        std::vector<double> linkeByMonth;
        const IrradianceParams params = inputsAt(source, point, request.rasters, constantInputs(request), &linkeByMonth);

        // Every instant's own sun and horizon, in parallel; summed below in time order.
        struct Instant {
            bool up = false;
            double hours = 0, sunHours = 0;
            CellIrradiance wm2;
        };
        std::vector<Instant> each(times.size());
        const std::vector<CellIndex> one{local};
        parallelFor(0, times.size(), [&](std::size_t i) {
            double distanceAu = 1;
            const SolarPosition sun = sunAt(point, times[i], request.atmosphere, &distanceAu);
            if (!(sun.elevationDeg > 0)) return;  // as the binned method: suns whose centre is up
            const double before = i > 0 ? instantHoursBetween(times[i - 1], times[i]) : 0.0;
            const double after = i + 1 < times.size() ? instantHoursBetween(times[i], times[i + 1]) : 0.0;
            HorizonParams hp = s.params;
            hp.azimuthDeg = sun.azimuthDeg;
            const double horizonDeg = referenceHorizonAt(d.terrain, hp, one).front().angleDeg;
            const CellView view = viewOf(n, horizonDeg, sun.azimuthDeg, sun.elevationDeg, request.sunDiameterDeg, out.skyK0);
            const ClearSky sky = clearSky(extraterrestrialIrradiance(distanceAu, request.solarConstantWm2),
                                          request.rasters.linke.empty() ? linkeAt(request.linke, times[i], request.zone)
                                          : linkeByMonth.empty()        ? params.linke
                                                                        : linkeByMonth[monthAt(times[i], request.zone)],
                                          sun.elevationDeg, point.heightM, params.coeffBh, params.coeffDh);
            each[i].up = true;
            each[i].hours = 0.5 * (before + after);
            each[i].sunHours = view.sunVisibility;
            each[i].wm2 = cellIrradiance(sky, view, params);
        }, 16);
        for (const Instant& e : each) {
            if (!e.up) continue;
            ++out.sunUpInstants;
            out.irradiation.beam += e.hours * e.wm2.beam / kWhPerKWh;
            out.irradiation.diffuse += e.hours * e.wm2.diffuse / kWhPerKWh;
            out.irradiation.reflected += e.hours * e.wm2.reflected / kWhPerKWh;
            out.sunHours += e.hours * e.sunHours;
        }
        return out;
    });
}

}  // namespace demlight
