#include "demlight/lighting/insolation.h"

#include "demlight/lighting/directions.h"
#include "demlight/lighting/esra.h"
#include "demlight/lighting/sun.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace demlight {

std::vector<SunBin> binSuns(const std::vector<WeightedSun>& suns, std::size_t directions, double elevationBandDeg) {
    if (directions < 1 || !(elevationBandDeg > 0)) throw Error("binSuns: need directions >= 1 and a band > 0");
    const double sector = 360.0 / static_cast<double>(directions);
    struct Sum {
        double hours = 0, azimuthOffset = 0, elevation = 0, g0 = 0;
    };
    std::map<std::tuple<std::size_t, long, double, int>, Sum> sums;  // ordered: by direction first
    for (const WeightedSun& s : suns) {
        if (!(s.elevationDeg > 0) || !(s.hours > 0)) continue;
        const double az = wrapAzimuthDeg(s.azimuthDeg);
        const auto direction = static_cast<std::size_t>(std::floor((az + sector / 2) / sector)) % directions;
        double offset = az - directionAzimuthDeg(direction, directions);  // within the sector, unwrapped
        if (offset > 180) offset -= 360;
        if (offset < -180) offset += 360;
        Sum& b = sums[{direction, static_cast<long>(std::floor(s.elevationDeg / elevationBandDeg)), s.linke,
                       s.month}];
        b.hours += s.hours;
        b.azimuthOffset += s.hours * offset;
        b.elevation += s.hours * s.elevationDeg;
        b.g0 += s.hours * s.extraterrestrialWm2;
    }
    std::vector<SunBin> bins;
    for (const auto& [key, b] : sums) {
        const std::size_t direction = std::get<0>(key);
        bins.push_back({direction, b.hours, directionAzimuthDeg(direction, directions) + b.azimuthOffset / b.hours,
                        b.elevation / b.hours, b.g0 / b.hours, std::get<2>(key), std::get<3>(key)});
    }
    return bins;
}

InsolationAccumulator::InsolationAccumulator(const Grid<float>& heightsM, const Normals& normals,
                                             std::vector<SunBin> bins, std::size_t directions,
                                             const IrradianceParams& params, double sunDiameterDeg)
    : heights_(heightsM),
      normals_(normals),
      bins_(std::move(bins)),
      directions_(directions),
      params_(params),
      sunDiameterDeg_(sunDiameterDeg),
      beam_(heightsM.width(), heightsM.height(), 0.0),
      diffuse_(beam_),
      reflected_(beam_),
      sunHours_(beam_) {
    for (float z : heightsM.values())
        if (!std::isnan(z)) {
            lowM_ = std::min(lowM_, static_cast<double>(z));
            highM_ = std::max(highM_, static_cast<double>(z));
        }
}

void InsolationAccumulator::setGrids(const ClearSkyGrids& grids) {
    for (const Grid<float>* g : {grids.linke, grids.albedo, grids.coeffBh, grids.coeffDh})
        if (g && !g->sameShape(heights_)) throw Error("InsolationAccumulator: a clear-sky grid of another shape");
    for (const Grid<float>* g : grids.linkeByMonth)
        if (grids.monthlyLinke() && (!g || !g->sameShape(heights_)))
            throw Error("InsolationAccumulator: monthly Linke grids must be twelve of the DEM's shape");
    for (const SunBin& b : bins_)
        if (b.month >= 12 || (b.month >= 0) != grids.monthlyLinke())
            throw Error("InsolationAccumulator: bins with a month need the twelve monthly Linke grids, and only they");
    grids_ = grids;
}

namespace {

DiskEdges diskEdges(double elevationDeg, double sunDiameterDeg) {
    const double low = elevationDeg - 0.5 * sunDiameterDeg, high = elevationDeg + 0.5 * sunDiameterDeg;
    return {low, high, std::tan(low * kDegToRad),
            high < 90 ? std::tan(high * kDegToRad) : std::numeric_limits<double>::infinity()};
}

/// sunTerms() of a bin's sun at a cell, skipped where the disk is wholly seen (above the horizon
/// and the tangent plane: O = 1, O max(0, N.s)) or wholly hidden below either (O = 0).
/// `toward` = N_east sin A + N_north cos A. The tests are strict (DiskEdges), so a horizon on an
/// edge takes sunTerms.
inline SunTerms binSunTerms(const Enu& n, double horizonDeg, const SunAngles& sun, const DiskEdges& e, double toward,
                            double sunDiameterDeg) {
    const bool up = n.up > 0;
    if (up && horizonDeg < e.lowDeg && -toward < n.up * e.tanLow)
        return {1.0, std::max(0.0, toward * sun.cosElevation + n.up * sun.sinElevation)};
    if (!std::isnan(horizonDeg) && (horizonDeg > e.highDeg || (up && -toward > n.up * e.tanHigh))) return {0.0, 0.0};
    return sunTerms(n, horizonDeg, sun, sunDiameterDeg);
}

}  // namespace

void InsolationAccumulator::addVisibleSky(const Grid<float>& horizonDeg, const std::vector<SunAngles>& angles,
                                          const std::vector<ClearSkySun>& skies,
                                          const std::vector<BeamNormalTable>& beams,
                                          const std::vector<DiskEdges>& edges,
                                          const std::vector<const SunBin*>& bins) {
    // The visible-sky model with constant inputs, the default: cellIrradiance's terms written out
    // (beam = B0c O max(0, N.s); diffuse and reflected horizon-free, Dhc and Ghc, times K0 and
    // albedo (1 - K0) in finish), in the same operations and order, so the same bits.
    std::vector<double> hours, diffuseHorizontal, sinElevation;
    for (std::size_t k = 0; k < bins.size(); ++k) {
        hours.push_back(bins[k]->hours);
        diffuseHorizontal.push_back(skies[k].diffuseHorizontal);
        sinElevation.push_back(skies[k].sinElevation);
    }
    parallelFor(0, heights_.height(), [&](std::size_t row) {
        for (std::size_t col = 0; col < heights_.width(); ++col) {
            const float z = heights_(col, row);
            if (std::isnan(z)) continue;
            const Enu n = normals_.at(col, row);
            const double horizon = horizonDeg(col, row);
            const BeamNormalTable::Node node = beams.front().node(z);
            double beam = beam_(col, row), sunHours = sunHours_(col, row), diffuse = diffuse_(col, row),
                   reflected = reflected_(col, row);
            for (std::size_t k = 0; k < bins.size(); ++k) {
                const SunAngles& sun = angles[k];
                const double beamNormal = beams[k].at(node, z);
                const double toward = n.east * sun.sinAzimuth + n.north * sun.cosAzimuth;
                const SunTerms terms = binSunTerms(n, horizon, sun, edges[k], toward, sunDiameterDeg_);
                beam += hours[k] * (beamNormal * terms.irradiance);
                sunHours += hours[k] * terms.visibility;
                diffuse += hours[k] * diffuseHorizontal[k];
                reflected += hours[k] * (beamNormal * sinElevation[k] + diffuseHorizontal[k]);
            }
            beam_(col, row) = beam;
            sunHours_(col, row) = sunHours;
            diffuse_(col, row) = diffuse;
            reflected_(col, row) = reflected;
        }
    });
}

void InsolationAccumulator::addDirection(std::size_t index, const Grid<float>& horizonDeg) {
    if (index >= directions_ || !horizonDeg.sameShape(heights_))
        throw Error("InsolationAccumulator: direction out of range or horizons of another shape");
    if (!(lowM_ <= highM_)) return;  // no valid cell
    std::vector<const SunBin*> bins;
    std::vector<SunAngles> angles;
    std::vector<ClearSkySun> skies;  // all but the cell's pressure ratio, once per bin
    std::vector<BeamNormalTable> beams;
    std::vector<DiskEdges> edges;
    for (const SunBin& b : bins_)
        if (b.direction == index) {
            bins.push_back(&b);
            const double az = b.azimuthDeg * kDegToRad, el = b.elevationDeg * kDegToRad;
            angles.push_back({b.azimuthDeg, b.elevationDeg, std::sin(az), std::cos(az), std::sin(el), std::cos(el)});
            skies.push_back(clearSkySun(b.extraterrestrialWm2, b.linke, b.elevationDeg, params_.coeffBh, params_.coeffDh));
            beams.emplace_back(skies.back(), lowM_, highM_);
            edges.push_back(diskEdges(b.elevationDeg, sunDiameterDeg_));
        }
    if (bins.empty()) return;
    const bool visibleSky = params_.model == DiffuseModel::VisibleSky;
    const bool skyGrid = grids_.changesSky(), anyGrid = skyGrid || grids_.albedo;
    if (visibleSky && !anyGrid) {
        addVisibleSky(horizonDeg, angles, skies, beams, edges, bins);
        return;
    }
    parallelFor(0, heights_.height(), [&](std::size_t row) {
        for (std::size_t col = 0; col < heights_.width(); ++col) {
            const float z = heights_(col, row);
            if (std::isnan(z)) continue;
            // The cell's own inputs only where grids are given: the constant path stays as it was.
            IrradianceParams own;
            const IrradianceParams* cell = &params_;
            if (anyGrid) {
                own = params_;
                if (!grids_.at(col, row, own)) continue;  // NaN in finish
                cell = &own;
            }
            const Enu n = normals_.at(col, row);
            const double horizon = horizonDeg(col, row);
            // Every table of the sector shares its nodes (the same lowM..highM).
            const BeamNormalTable::Node node = beams.front().node(z);
            // The cell's slope terms of the rsun model, once for all its bins.
            const MuneerSlope slope = visibleSky ? MuneerSlope{} : muneerSlope(n.up);
            // Summed in registers, in the same order as into the grids.
            double beam = beam_(col, row), hours = sunHours_(col, row), diffuse = diffuse_(col, row),
                   reflected = reflected_(col, row);
            for (std::size_t k = 0; k < bins.size(); ++k) {
                const SunBin& b = *bins[k];
                const SunAngles& sun = angles[k];
                // A per-cell Linke or index: the bin's sky at this cell from the formulas (E2-E9).
                const double linke = b.month >= 0 ? (*grids_.linkeByMonth[static_cast<std::size_t>(b.month)])(col, row)
                                     : grids_.linke ? cell->linke
                                                    : b.linke;
                const ClearSky sky = skyGrid ? clearSky(b.extraterrestrialWm2, linke, b.elevationDeg, z, cell->coeffBh,
                                                        cell->coeffDh)
                                             : clearSkyWithBeam(skies[k], beams[k].at(node, z));
                const double toward = n.east * sun.sinAzimuth + n.north * sun.cosAzimuth;
                const double cosine = toward * sun.cosElevation + n.up * sun.sinElevation;
                const SunTerms terms = binSunTerms(n, horizon, sun, edges[k], toward, sunDiameterDeg_);
                CellView view;
                view.sunIrradiance = terms.irradiance;
                view.sunVisibility = terms.visibility;
                view.surface = {n.up, toward, cosine, b.elevationDeg * kDegToRad};
                const CellIrradiance c = cellIrradiance(sky, view, *cell, slope);
                beam += b.hours * c.beam;
                hours += b.hours * terms.visibility;
                // visible-sky: diffuse and reflected are K0 and 1 - K0 times horizon-free sums.
                diffuse += b.hours * (visibleSky ? sky.diffuseHorizontal : c.diffuse);
                reflected += b.hours * (visibleSky ? sky.globalHorizontal() : c.reflected);
            }
            beam_(col, row) = beam;
            sunHours_(col, row) = hours;
            diffuse_(col, row) = diffuse;
            reflected_(col, row) = reflected;
        }
    });
}

InsolationMaps InsolationAccumulator::finish(const Grid<float>* skyK0) const {
    const bool visibleSky = params_.model == DiffuseModel::VisibleSky;
    if (visibleSky && (!skyK0 || !skyK0->sameShape(heights_)))
        throw Error("InsolationAccumulator: the visible-sky model needs K0 of the DEM's shape");
    const std::size_t w = heights_.width(), h = heights_.height();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    InsolationMaps totals{{Grid<float>(w, h, nan), Grid<float>(w, h, nan), Grid<float>(w, h, nan), Grid<float>(w, h, nan)},
                          Grid<float>(w, h, nan)};
    IrradianceMaps& out = totals.irradiation;
    for (std::size_t k = 0; k < heights_.size(); ++k) {
        if (std::isnan(heights_.data()[k])) continue;
        IrradianceParams cell = params_;
        if (!grids_.at(k % w, k / w, cell)) continue;
        const double beam = beam_.data()[k];
        double diffuse = diffuse_.data()[k], reflected = reflected_.data()[k];
        if (visibleSky) {
            const double k0 = std::clamp(static_cast<double>(skyK0->data()[k]), 0.0, 1.0);
            diffuse *= k0;
            reflected *= cell.albedo * (1 - k0);
        }
        out.beam.data()[k] = static_cast<float>(beam);
        out.diffuse.data()[k] = static_cast<float>(diffuse);
        out.reflected.data()[k] = static_cast<float>(reflected);
        out.global.data()[k] = static_cast<float>(beam + diffuse + reflected);
        totals.sunHours.data()[k] = static_cast<float>(sunHours_.data()[k]);
    }
    return totals;
}

}  // namespace demlight
