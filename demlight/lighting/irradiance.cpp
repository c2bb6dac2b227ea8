#include "demlight/lighting/irradiance.h"

#include "demlight/lighting/sun_frame.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace demlight {

DiffuseModel parseDiffuseModel(std::string_view name) {
    if (name == "visible-sky") return DiffuseModel::VisibleSky;
    if (name == "rsun") return DiffuseModel::RSun;
    throw FieldError("diffuseModel", " '" + std::string(name) + "': expected visible-sky or rsun");
}

std::string_view diffuseModelName(DiffuseModel model) {
    return model == DiffuseModel::RSun ? "rsun" : "visible-sky";
}

void raiseToHorizontal(const Grid<float>& horizonDeg, Grid<float>& raised) {
    raised = horizonDeg;
    for (float& v : raised.values()) v = std::max(v, 0.0f);  // NaN stays NaN
}

bool ClearSkyGrids::at(std::size_t col, std::size_t row, IrradianceParams& params) const {
    for (const auto& [grid, value] : {std::pair{linke, &params.linke}, std::pair{albedo, &params.albedo},
                                      std::pair{coeffBh, &params.coeffBh}, std::pair{coeffDh, &params.coeffDh}}) {
        if (!grid) continue;
        const float v = (*grid)(col, row);
        if (std::isnan(v)) return false;
        *value = v;
    }
    if (monthlyLinke())
        for (const Grid<float>* grid : linkeByMonth)
            if (std::isnan((*grid)(col, row))) return false;
    return true;
}

CellIrradiance cellIrradiance(const ClearSky& sky, const CellView& view, const IrradianceParams& params) {
    return cellIrradiance(sky, view, params,
                          params.model == DiffuseModel::RSun ? muneerSlope(view.surface.normalUp) : MuneerSlope{});
}

CellIrradiance cellIrradiance(const ClearSky& sky, const CellView& view, const IrradianceParams& params,
                              const MuneerSlope& slope) {
    CellIrradiance out;
    if (!(sky.beamNormal > 0 || sky.diffuseHorizontal > 0)) return out;  // the sun is down
    out.beam = sky.beamNormal * view.sunIrradiance;
    if (params.model == DiffuseModel::VisibleSky) {
        const double k0 = std::clamp(view.skyK0, 0.0, 1.0);
        out.diffuse = sky.diffuseHorizontal * k0;
        out.reflected = params.albedo * sky.globalHorizontal() * (1 - k0);
        return out;
    }
    // r.sun: Kb of the sunlit case from the unshadowed beam (drad's bh / (G0 sin h)).
    const double kb = sky.extraterrestrial > 0 ? sky.beamNormal / sky.extraterrestrial : 0.0;
    out.diffuse = muneerDiffuse(sky.diffuseHorizontal, kb, view.surface, view.sunVisibility, slope);
    const double cosG = slope.cosG;
    const double seenBeam = view.surface.cosIncidence > 0 ? view.sunVisibility * sky.beamHorizontal : 0.0;
    out.reflected = params.albedo * (seenBeam + sky.diffuseHorizontal) * (1 - cosG) / 2;  // E12
    return out;
}

IrradianceMaps computeIrradiance(const IrradianceInputs& in, const IrradianceParams& p) {
    if (!in.heightsM || !in.normals || !in.sun || !in.sunVisibility || !in.sunIrradiance ||
        (p.model == DiffuseModel::VisibleSky && !in.skyK0))
        throw Error("computeIrradiance: an input grid is missing");
    const Grid<float>& heights = *in.heightsM;
    const std::size_t width = heights.width(), height = heights.height();
    const auto sameShape = [&](const Grid<float>& g) { return g.width() == width && g.height() == height; };
    bool gridsFit = true;
    for (const Grid<float>* g : {in.grids.linke, in.grids.albedo, in.grids.coeffBh, in.grids.coeffDh})
        gridsFit = gridsFit && (!g || sameShape(*g));
    if (!sameShape(in.normals->up) || !sameShape(*in.sunVisibility) || !sameShape(*in.sunIrradiance) ||
        (in.skyK0 && !sameShape(*in.skyK0)) || !gridsFit)
        throw Error("computeIrradiance: the input grids differ in shape");

    const float nan = std::numeric_limits<float>::quiet_NaN();
    IrradianceMaps out{Grid<float>(width, height, nan), Grid<float>(width, height, nan),
                       Grid<float>(width, height, nan), Grid<float>(width, height, nan)};
    const Normals& n = *in.normals;
    const bool anyGrid = in.grids.changesSky() || in.grids.albedo;
    parallelFor(0, height, [&](std::size_t row) {
        forEachSunInRow(*in.sun, row, width, [&](std::size_t col, const SunAngles& sun) {
            const float z = heights(col, row);
            if (std::isnan(z)) return;
            IrradianceParams q = p;  // the cell's own inputs where grids are given
            if (anyGrid && !in.grids.at(col, row, q)) return;
            const ClearSky sky = clearSky(q.extraterrestrialWm2, q.linke, sun.elevationDeg, z, q.coeffBh, q.coeffDh);
            CellView view;
            view.sunIrradiance = (*in.sunIrradiance)(col, row);
            view.sunVisibility = (*in.sunVisibility)(col, row);
            const double up = n.up(col, row);
            // The normal's horizontal part along the sun's azimuth, and N.s, as the sun frame takes them.
            const double toward = n.east(col, row) * sun.sinAzimuth + n.north(col, row) * sun.cosAzimuth;
            view.surface = {up, toward, toward * sun.cosElevation + up * sun.sinElevation, sun.elevationDeg * kDegToRad};
            if (in.skyK0) view.skyK0 = (*in.skyK0)(col, row);
            const CellIrradiance c = cellIrradiance(sky, view, q);
            out.beam(col, row) = static_cast<float>(c.beam);
            out.diffuse(col, row) = static_cast<float>(c.diffuse);
            out.reflected(col, row) = static_cast<float>(c.reflected);
            out.global(col, row) = static_cast<float>(c.global());
        });
    });
    return out;
}

}  // namespace demlight
