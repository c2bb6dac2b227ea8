#include "demlight/lighting/lighting_models.h"

#include "demlight/lighting/sun.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace demlight {

namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

double dot(const EnuVector& a, const EnuVector& b) {
    return a.east * b.east + a.north * b.north + a.up * b.up;
}

/// The aperture of a cell and its normal; false if any component is NaN.
bool cellAperture(const ApertureMaps& a, const Grid<float>& ne, const Grid<float>& nn,
                  const Grid<float>& nu, std::size_t col, std::size_t row, Aperture& ap,
                  EnuVector& n) {
    ap = Aperture{a.solidAngleSr(col, row),
                  {a.bentEast(col, row), a.bentNorth(col, row), a.bentUp(col, row)},
                  a.radiusDeg(col, row)};
    n = EnuVector{ne(col, row), nn(col, row), nu(col, row)};
    return !(std::isnan(ap.solidAngleSr) || std::isnan(ap.radiusDeg) ||
             std::isnan(ap.bentNormal.east) || std::isnan(ap.bentNormal.north) ||
             std::isnan(ap.bentNormal.up) || std::isnan(n.east) || std::isnan(n.north) ||
             std::isnan(n.up));
}

}  // namespace

SunModel parseSunModel(std::string_view name) {
    if (name == "horizon") return SunModel::Horizon;
    if (name == "aperture") return SunModel::Aperture;
    if (name == "aperture-smooth") return SunModel::ApertureSmooth;
    if (name == "hemisphere")
        throw Error("sun model 'hemisphere': Hargreaves' hemisphere is a sky-only model (no sun term); "
                    "it is a sky model. Sun models: horizon, aperture or aperture-smooth");
    throw Error("unknown sun model '" + std::string(name) + "' (expected horizon, aperture or aperture-smooth)");
}

std::string_view sunModelName(SunModel model) {
    switch (model) {
        case SunModel::Horizon: return "horizon";
        case SunModel::Aperture: return "aperture";
        case SunModel::ApertureSmooth: return "aperture-smooth";
    }
    return "unknown";
}

SkyModel parseSkyModel(std::string_view name) {
    if (name == "stewart-langer") return SkyModel::StewartLanger;
    if (name == "hemisphere") return SkyModel::Hemisphere;
    if (name == "none") return SkyModel::None;
    throw Error("unknown sky model '" + std::string(name) + "' (expected stewart-langer, hemisphere or none)");
}

std::string_view skyModelName(SkyModel model) {
    switch (model) {
        case SkyModel::StewartLanger: return "stewart-langer";
        case SkyModel::Hemisphere: return "hemisphere";
        case SkyModel::None: return "none";
    }
    return "unknown";
}

ApertureLight apertureLight(const EnuVector& normal, const Aperture& ap,
                            const EnuVector& sunDirection, const ApertureLightParams& params) {
    // Oat & Sander Sec. 3: intersect the light cap with the aperture cap.
    const double rl = params.sunRadiusDeg * kDegToRad;
    const double rp = ap.radiusDeg * kDegToRad;
    const double d = std::acos(std::clamp(dot(sunDirection, ap.bentNormal), -1.0, 1.0));
    const double area = params.smoothIntersection ? capIntersectionAreaSmoothSr(rp, rl, d)
                                                  : capIntersectionAreaSr(rp, rl, d);
    const double sunArea = capAreaSr(rl);
    ApertureLight out;
    if (sunArea > 0.0) out.sunVisible = std::clamp(area / sunArea, 0.0, 1.0);
    if (area > 0.0 && sunArea > 0.0) {
        if (params.smoothIntersection) {
            // Seed Sec. 3.3: area times the Lambert term at the (cheap) centroid direction.
            const EnuVector c = capIntersectionCentroidFast(sunDirection, rl, ap.bentNormal, rp);
            out.sun = params.sunRadiance * (area / sunArea) * std::max(0.0, dot(normal, c));
        } else {
            // Exact: integral over the intersection of N.v = N . (area * mean direction).
            // Normalised by the disk's own integral at normal incidence, pi sin^2 r_l, so a
            // fully visible sun gives exactly max(0, N.s) as in Hoffman & Mitchell Eq. 3.
            const EnuVector m = capIntersectionVector(sunDirection, rl, ap.bentNormal, rp);
            const double sinRl = std::sin(rl);
            out.sun = params.sunRadiance * std::max(0.0, dot(normal, m)) /
                      (std::numbers::pi * sinRl * sinRl);
        }
    }
    // Ambient fill of the uncovered aperture (Sec. 3.3, "Ambient lighting").
    if (ap.solidAngleSr > 0.0) {
        const double s = std::sin(rp);
        const double uncovered = std::clamp(1.0 - area / ap.solidAngleSr, 0.0, 1.0);
        out.ambient = params.ambientRadiance * s * s *
                      std::max(0.0, dot(normal, ap.bentNormal)) * uncovered;
    }
    return out;
}

namespace {

/// Checks that the aperture and normal grids agree, then calls light(col, row, aperture, normal)
/// for every cell that has both, in parallel over rows.
template <class Fn>
void forEachApertureCell(const ApertureMaps& aperture, const Grid<float>& normalEast,
                         const Grid<float>& normalNorth, const Grid<float>& normalUp,
                         Fn&& light) {
    const Grid<float>& ref = aperture.radiusDeg;
    for (const Grid<float>* g : {&aperture.bentEast, &aperture.bentNorth, &aperture.bentUp,
                                 &aperture.solidAngleSr, &normalEast, &normalNorth, &normalUp})
        if (!g->sameShape(ref))
            throw Error("aperture lighting: aperture and normal grids differ in size");
    parallelFor(0, ref.height(), [&](std::size_t row) {
        for (std::size_t col = 0; col < ref.width(); ++col) {
            Aperture ap;
            EnuVector n;
            if (cellAperture(aperture, normalEast, normalNorth, normalUp, col, row, ap, n))
                light(col, row, ap, n);
        }
    });
}

}  // namespace

ApertureLightMaps applyApertureLight(const ApertureMaps& aperture, const Grid<float>& normalEast,
                                     const Grid<float>& normalNorth, const Grid<float>& normalUp,
                                     const EnuVector& sunDirection,
                                     const ApertureLightParams& params) {
    const Grid<float>& ref = aperture.radiusDeg;
    ApertureLightMaps out{Grid<float>(ref.width(), ref.height(), kNaNf),
                          Grid<float>(ref.width(), ref.height(), kNaNf)};
    forEachApertureCell(aperture, normalEast, normalNorth, normalUp,
                        [&](std::size_t col, std::size_t row, const Aperture& ap, const EnuVector& n) {
                            const ApertureLight l = apertureLight(n, ap, sunDirection, params);
                            out.sun(col, row) = static_cast<float>(l.sun);
                            out.ambient(col, row) = static_cast<float>(l.ambient);
                        });
    return out;
}

ApertureSunMaps applyApertureSun(const ApertureMaps& aperture, const Grid<float>& normalEast,
                                 const Grid<float>& normalNorth, const Grid<float>& normalUp,
                                 const SunField& field, const ApertureLightParams& params) {
    const Grid<float>& ref = aperture.radiusDeg;
    ApertureSunMaps out{Grid<float>(ref.width(), ref.height(), kNaNf),
                        Grid<float>(ref.width(), ref.height(), kNaNf)};
    forEachApertureCell(aperture, normalEast, normalNorth, normalUp,
                        [&](std::size_t col, std::size_t row, const Aperture& ap, const EnuVector& n) {
                            // Per-cell sun, as computeSunFrame uses for the horizon model.
                            const auto [az, el] = field.at(static_cast<double>(col) + 0.5,
                                                           static_cast<double>(row) + 0.5);
                            const ApertureLight l = apertureLight(n, ap, directionEnu(az, el), params);
                            out.visibility(col, row) = static_cast<float>(l.sunVisible);
                            out.irradiance(col, row) = static_cast<float>(l.sun);
                        });
    return out;
}

double hemisphereLight(double normalUp, double skyRadiance, double groundRadiance) {
    // Hargreaves 2003: blend sky and ground colour by the normal's up component.
    const double u = std::clamp(normalUp, -1.0, 1.0);
    return skyRadiance * 0.5 * (1.0 + u) + groundRadiance * 0.5 * (1.0 - u);
}

Grid<float> applyHemisphereLight(const Grid<float>& normalUp, const HemisphereParams& params,
                                 const Grid<float>* albedo) {
    if (albedo && !albedo->sameShape(normalUp))
        throw Error("hemisphere lighting: albedo grid size differs from the DEM");
    Grid<float> out(normalUp.width(), normalUp.height(), kNaNf);
    parallelFor(0, normalUp.height(), [&](std::size_t row) {
        for (std::size_t col = 0; col < normalUp.width(); ++col) {
            const double c = albedo ? (*albedo)(col, row) : params.albedo;
            const double u = normalUp(col, row);
            if (std::isnan(c) || std::isnan(u)) continue;
            out(col, row) = static_cast<float>(
                hemisphereLight(u, params.skyRadiance, c * params.groundIrradiance));
        }
    });
    return out;
}

}  // namespace demlight
