#include "demlight/lighting/sky.h"

#include "demlight/lighting/sky_wedge.h"
#include "demlight/lighting/sky_wedge_lanes.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace demlight {


using detail::kHalfPi;
using detail::kPi;

namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
constexpr float kDegToRadF = static_cast<float>(kDegToRad);

double clampElevationRad(double elevationDeg) {
    return std::clamp(elevationDeg, -90.0, 90.0) * kDegToRad;
}

/// Integral of a(phi) = N_e sin phi + N_n cos phi over [phiA, phiB].
double integralOfA(const detail::NormalFrame& f, double phiA, double phiB) {
    const SinCos a = fastSinCos(phiA), b = fastSinCos(phiB);
    return f.east * (a.cos - b.cos) + f.north * (b.sin - a.sin);
}

/// J(psi) = integral of R sin(psi) atan(k sin(psi)) d psi with k = R / N_up, in elementary
/// form: by parts, then integral d psi / (1 + k^2 sin^2 psi) = (1/m) atan(m tan psi),
/// m = sqrt(1 + k^2), written without the branch jump as
/// psi + atan((m - 1) sin cos / (cos^2 + m sin^2)).
double planeAntiderivative(const detail::NormalFrame& f, double psi) {
    const double k = f.horizontal / f.up;
    const double m = std::sqrt(1.0 + k * k);
    const double mMinus1 = k * k / (m + 1.0);
    const auto [s, c] = fastSinCos(psi);
    // fastAtan (3e-9 rad) in place of std::atan: this runs for every sector whose tangent plane
    // rises above the horizon, the dearest case of the sky accumulation.
    return -f.horizontal * c * fastAtan(k * s) +
           f.up * (mMinus1 * psi + m * fastAtan(mMinus1 * s * c / (c * c + m * s * s)));
}

/// pi * K over one piece of a wedge.
double piecePiK(const detail::NormalFrame& f, double phiA, double phiB, double lower, double upper,
                detail::PieceLower kind) {
    const double aInt = integralOfA(f, phiA, phiB);
    const double width = phiB - phiA;
    // Upper limit: integral_el^upper (a cos el + N_up sin el) cos el d el.
    double piK = aInt * detail::cos2Antiderivative(upper) +
                 f.up * width * detail::sinCosAntiderivative(upper);
    if (kind == detail::PieceLower::Constant) {
        piK -= aInt * detail::cos2Antiderivative(lower) +
               f.up * width * detail::sinCosAntiderivative(lower);
    } else if (f.horizontal >= detail::kFlatNormalEps) {
        // On the tangent plane a T(thetaP) + N_up S(thetaP) = a thetaP / 2
        // = -a atan(a / N_up) / 2, whose integral is -J / 2.
        piK += 0.5 * (planeAntiderivative(f, phiB + f.delta) -
                      planeAntiderivative(f, phiA + f.delta));
    }
    return piK;
}

double wedgeK(const detail::NormalFrame& f, double phi1, double phi2, double lower, double upper) {
    double piK = 0.0;
    detail::forEachWedgePiece(f, phi1, phi2, lower, upper,
                              [&](double a, double b, detail::PieceLower kind) {
                                  piK += piecePiK(f, a, b, lower, upper, kind);
                              });
    return piK / kPi;
}

/// K of a wedge with the fast path: when the tangent plane stays below the lower limit across
/// the range (the common case on real terrain), the constant-limit closed form applies
/// directly with sines and cosines of the range ends precomputed; otherwise the general cut.
double wedgeKFast(const EnuVector& n, const detail::AzimuthRange& r, double lower, double sinL,
                  double cosL, double upper) {
    if (!(lower < upper)) return 0.0;
    const double nu = n.up;
    if (detail::planeBelowAcross(r, n.east, n.north, nu, sinL, cosL)) {
        const double aInt = n.east * (r.cos1 - r.cos2) + n.north * (r.sin2 - r.sin1);
        const double width = r.phi2 - r.phi1;
        const double cos2 =
            detail::cos2Antiderivative(upper) - (0.5 * lower + 0.5 * sinL * cosL);
        const double sinCos = detail::sinCosAntiderivative(upper) - 0.5 * sinL * sinL;
        return (aInt * cos2 + nu * width * sinCos) / kPi;
    }
    const detail::NormalFrame f = detail::makeNormalFrame(n);
    // The tangent plane above the lower limit across the whole range (and the zenith as upper
    // limit, which the plane never reaches): one plane piece, the piece forEachWedgePiece would
    // find, without searching for cuts.
    if (upper >= kHalfPi && f.horizontal >= detail::kFlatNormalEps &&
        detail::planeAboveAcross(r, n.east, n.north, nu, sinL, cosL))
        return piecePiK(f, r.phi1, r.phi2, lower, upper, detail::PieceLower::Plane) / kPi;
    return wedgeK(f, r.phi1, r.phi2, lower, upper);
}

double wedgeKFast(const EnuVector& n, const detail::AzimuthRange& r, double lower, double upper) {
    return wedgeKFast(n, r, lower, std::sin(lower), std::cos(lower), upper);
}


/// A sector's constants for accumulateRowFast, in float.
struct FastSector {
    float sin1, cos1, sin2, cos2;
    float cosDrop, sinRise;  // cos phi1 - cos phi2, sin phi2 - sin phi1
    float width;             // radians
    bool narrow;             // narrower than pi: detail::planeBelowAcross and
                             // detail::sectorPiKAboveLower apply
};

FastSector makeFastSector(const detail::AzimuthRange& r) {
    return {static_cast<float>(r.sin1),           static_cast<float>(r.cos1),
            static_cast<float>(r.sin2),           static_cast<float>(r.cos2),
            static_cast<float>(r.cos1 - r.cos2),  static_cast<float>(r.sin2 - r.sin1),
            static_cast<float>(r.phi2 - r.phi1),  r.phi2 - r.phi1 < kPi};
}

/// One row of one sector, branch-free so the compiler vectorises it, in float (the sums are
/// float):
/// - sin max(h, 0) into the two SVF sums of every cell;
/// - K of every tilted cell whose tangent plane stays below its horizon across the sector (the
///   constant-limit closed form, as in wedgeKFast); the others get rises = 1 and are left to the
///   caller. Flat cells take K from the SVF sum in SkyAccumulator::finish and add nothing here.
/// NaN inputs give NaN. The pointers do not alias (restrict: seven arrays are more than the
/// vectoriser checks at run time). Inlined into accumulateRowFast.
DEMLIGHT_INLINE inline void accumulateRowFastLoop(const float* __restrict h, const float* __restrict e,
                                                  const float* __restrict n, const float* __restrict u,
                                                  float* __restrict k, float* __restrict s1, float* __restrict s2,
                                                  std::uint8_t* __restrict rises, std::size_t cols,
                                                  const FastSector c) {
    constexpr float kPiF = static_cast<float>(kPi);
    constexpr auto kFlatEps2 = static_cast<float>(detail::kFlatNormalEps * detail::kFlatNormalEps);
    for (std::size_t col = 0; col < cols; ++col) {
        const float hc = h[col], ec = e[col], nc = n[col], uc = u[col];
        const float lower = std::clamp(hc, -90.0f, 90.0f) * kDegToRadF;  // NaN stays NaN
        const float sinL = fastSinElevationF(lower);
        const float cosL = std::sqrt(std::max(0.0f, 1.0f - sinL * sinL));  // |lower| <= pi/2
        const float sPos = lower > 0.0f ? sinL : (lower != lower ? lower : 0.0f);
        s1[col] += sPos;
        s2[col] += sPos * sPos;

        const float up = std::max(uc, static_cast<float>(kMinNormalUp));  // NaN stays NaN
        const float inverseLength = 1.0f / std::sqrt(ec * ec + nc * nc + up * up);
        const float ne = ec * inverseLength, nn = nc * inverseLength, nu = up * inverseLength;
        const float horizontal2 = ne * ne + nn * nn;
        const float aInt = ne * c.cosDrop + nn * c.sinRise;
        const float kConstant = (aInt * (kPiF / 4.0f - 0.5f * lower - 0.5f * sinL * cosL) +
                                 nu * c.width * (0.5f - 0.5f * sinL * sinL)) /
                                kPiF;
        // detail::planeBelowAcross: the lowest a(phi) over the sector against `lower`.
        const float aMin = detail::lowestA(ne, nn, c.sin1, c.cos1, c.sin2, c.cos2);
        const bool flat = horizontal2 < kFlatEps2;
        const bool planeRises = !flat && (!c.narrow || aMin * cosL + nu * sinL < 0.0f);
        const float add = flat ? hc * 0.0f + uc * 0.0f : kConstant;
        k[col] += planeRises ? 0.0f : add;
        rises[col] = planeRises;
    }
}

/// accumulateRowFastLoop on the widest SimdPath.
void accumulateRowFast(const float* h, const float* e, const float* n, const float* u, float* k, float* s1,
                       float* s2, std::uint8_t* rises, std::size_t cols, const FastSector& c) {
    onWidestPath([&]() DEMLIGHT_INLINE { accumulateRowFastLoop(h, e, n, u, k, s1, s2, rises, cols, c); });
}

/// Overlap of a sector (radians) with every patch, shifting patches by whole turns.
struct PatchPiece {
    std::size_t patch;
    detail::AzimuthRange range;
    double lowerRad, upperRad;
};

std::vector<PatchPiece> sectorPatchPieces(std::size_t sector, std::size_t count,
                                          const SkyPatches& patches) {
    std::vector<PatchPiece> pieces;
    const auto [s0, s1] = detail::sectorBoundsRad(sector, count);
    for (std::size_t p = 0; p < patches.size(); ++p) {
        const SkyPatch& patch = patches.patches[p];
        for (int turn = -2; turn <= 2; ++turn) {
            const double a0 = patch.azimuth0Deg * kDegToRad + 2.0 * kPi * turn;
            const double a1 = patch.azimuth1Deg * kDegToRad + 2.0 * kPi * turn;
            const double lo = std::max(a0, s0), hi = std::min(a1, s1);
            if (lo < hi)
                pieces.push_back({p, detail::makeAzimuthRange(lo, hi),
                                  clampElevationRad(patch.elevation0Deg),
                                  clampElevationRad(patch.elevation1Deg)});
        }
    }
    return pieces;
}

std::string trimmed(std::string_view s) {
    std::string out;
    for (char c : s)
        if (c != ' ' && c != '\t') out.push_back(c);
    return out;
}

double parseNumber(const std::string& token, std::string_view what) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || end != token.data() + token.size() || !std::isfinite(value))
        throw FieldError("patches", ": '" + token + "' is not a number (expected " + std::string(what) +
                    ")");
    return value;
}

std::string formatDeg(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

void checkCellInputs(const Grid<float>& e, const Grid<float>& n, const Grid<float>& u) {
    if (!e.sameShape(n) || !e.sameShape(u))
        throw Error("sky: the east, north and up normal grids differ in size");
}

}  // namespace

double svfHorizontal(std::span<const float> horizonDeg) {
    // Dozier & Frew 1990: V_d = (1/2pi) integral cos^2 h d phi for a horizontal surface.
    double sum = 0.0;
    for (float h : horizonDeg) {
        const double s = std::sin(clampElevationRad(std::max(0.0, static_cast<double>(h))));
        sum += s * s;
    }
    return 1.0 - sum / static_cast<double>(horizonDeg.size());
}

double skyFraction(std::span<const float> horizonDeg) {
    // Zaksek, Ostir & Kokalj 2011: SVF = 1 - mean sin h (unweighted solid-angle fraction).
    double sum = 0.0;
    for (float h : horizonDeg)
        sum += std::sin(clampElevationRad(std::max(0.0, static_cast<double>(h))));
    return 1.0 - sum / static_cast<double>(horizonDeg.size());
}

double skyKWedge(const EnuVector& normal, double az0Deg, double az1Deg, double horizonDeg,
                 double bandLowDeg, double bandHighDeg) {
    const detail::NormalFrame f = detail::makeNormalFrame(detail::unitNormal(normal));
    return wedgeK(f, az0Deg * kDegToRad, az1Deg * kDegToRad,
                  clampElevationRad(std::max(horizonDeg, bandLowDeg)),
                  clampElevationRad(bandHighDeg));
}

double skyK(std::span<const float> horizonDeg, const EnuVector& normalIn) {
    const EnuVector normal = detail::unitNormal(normalIn);
    // Stewart & Langer 1997 (Hoffman & Mitchell 2001b, Eq. 9-12), exact per sector with per-azimuth
    // clamping.
    const detail::NormalFrame f = detail::makeNormalFrame(normal);
    // Horizontal tangent plane: every sector integrates to N_up cos^2 max(h, 0) / D; summing
    // the weights before dividing keeps open flat ground at exactly 1.
    if (f.horizontal < detail::kFlatNormalEps) return f.up * svfHorizontal(horizonDeg);
    double sum = 0.0;
    for (std::size_t i = 0; i < horizonDeg.size(); ++i) {
        const auto [phi1, phi2] = detail::sectorBoundsRad(i, horizonDeg.size());
        sum += wedgeKFast(normal, detail::makeAzimuthRange(phi1, phi2),
                          clampElevationRad(horizonDeg[i]), kHalfPi);
    }
    return sum;
}

Grid<float> skyFactorOf(const Grid<float>& skyK, const Grid<float>* albedo, double constantAlbedo) {
    if (albedo && !albedo->sameShape(skyK)) throw Error("sky: albedo grid size differs from the sky K grid");
    Grid<float> out(skyK.width(), skyK.height());
    for (std::size_t i = 0; i < skyK.size(); ++i) {
        const double k = skyK.data()[i], c = albedo ? albedo->data()[i] : constantAlbedo;
        out.data()[i] = std::isnan(k) || std::isnan(c) ? kNaNf : static_cast<float>(skyFactor(k, c));
    }
    return out;
}

double skyFactor(double skyK, double albedo) {
    // Hoffman & Mitchell 2001b, Eq. 8 (Stewart & Langer's interreflection approximation).
    const double k = std::clamp(skyK, 0.0, 1.0);
    const double c = std::clamp(albedo, 0.0, 1.0);
    if (!(k > 0.0)) return 0.0;
    // 1 - C(1 - K) written as (1 - C) + C K: no cancellation when C -> 1 and K -> 0.
    return std::min(1.0, k / ((1.0 - c) + c * k));
}

SkyPatches parseSkyPatches(std::string_view specIn) {
    const std::string spec = trimmed(specIn);
    SkyPatches result;
    result.spec = std::string(specIn);
    if (spec == "sky") {
        result.patches.push_back({0.0, 360.0, -90.0, 90.0, "sky"});
        return result;
    }
    // Tokens separated by ','; a token "key:value" starts a key, bare tokens continue its list.
    int sectors = 0;
    std::vector<double> bands;
    std::string key;
    std::stringstream in(spec);
    std::string token;
    bool any = false;
    while (std::getline(in, token, ',')) {
        any = true;
        if (const auto colon = token.find(':'); colon != std::string::npos) {
            key = token.substr(0, colon);
            token = token.substr(colon + 1);
            if (key == "sectors") {
                if (sectors != 0) throw FieldError("patches", ": 'sectors' given twice");
                const double n = parseNumber(token, "a whole number of sectors 1..360");
                if (n != std::floor(n) || n < 1 || n > 360)
                    throw FieldError("patches", ": sectors:" + token +
                                " is not a whole number of sectors in 1..360");
                sectors = static_cast<int>(n);
                continue;
            }
            if (key == "bands") {
                if (!bands.empty()) throw FieldError("patches", ": 'bands' given twice");
            } else {
                throw FieldError("patches", ": unknown key '" + key +
                            "' (expected 'sky', 'sectors:N', 'bands:E0,...,90' or both "
                            "'sectors:N,bands:E0,...,90')");
            }
        }
        if (key != "bands")
            throw FieldError("patches", ": '" + token +
                        "' is not part of a list (expected 'sectors:N' or 'bands:E0,...,90')");
        bands.push_back(parseNumber(token, "an elevation band edge in degrees"));
    }
    if (!any || (sectors == 0 && bands.empty()))
        throw FieldError("patches", ": empty spec (expected 'sky', 'sectors:N', 'bands:E0,...,90' or "
                    "'sectors:N,bands:E0,...,90')");
    if (!bands.empty()) {
        if (bands.size() < 2)
            throw FieldError("patches", ": bands need at least two edges, e.g. bands:0,90");
        for (std::size_t i = 1; i < bands.size(); ++i)
            if (!(bands[i] > bands[i - 1]))
                throw FieldError("patches", ": band edges must increase strictly (got " +
                            formatDeg(bands[i - 1]) + " then " + formatDeg(bands[i]) + ")");
        if (bands.front() < -90.0 || bands.front() >= 90.0)
            throw FieldError("patches", ": the first band edge must be in [-90, 90) degrees");
        if (bands.back() != 90.0)
            throw FieldError("patches", ": the last band edge must be 90 (the zenith), got " +
                        formatDeg(bands.back()));
    } else {
        bands = {-90.0, 90.0};
    }
    const int sectorCount = std::max(sectors, 1);
    const double width = 360.0 / sectorCount;
    for (int s = 0; s < sectorCount; ++s) {
        const double az0 = sectorCount == 1 ? 0.0 : (s - 0.5) * width;
        const double az1 = sectorCount == 1 ? 360.0 : (s + 0.5) * width;
        for (std::size_t b = 0; b + 1 < bands.size(); ++b) {
            // The first band reaches down to -90 so that the patches partition the sphere.
            const double el0 = b == 0 ? -90.0 : bands[b];
            const double el1 = bands[b + 1];
            result.patches.push_back(
                {az0, az1, el0, el1,
                 "az " + formatDeg(az0) + ".." + formatDeg(az1) + " el " + formatDeg(el0) +
                     ".." + formatDeg(el1)});
        }
    }
    return result;
}

void skyPatchK(std::span<const float> horizonDeg, const EnuVector& normalIn,
               const SkyPatches& patches, std::span<double> out) {
    const EnuVector normal = detail::unitNormal(normalIn);
    if (out.size() != patches.size())
        throw Error("skyPatchK: output span size differs from the number of patches");
    std::fill(out.begin(), out.end(), 0.0);
    for (std::size_t i = 0; i < horizonDeg.size(); ++i) {
        const double h = clampElevationRad(horizonDeg[i]);
        for (const PatchPiece& p : sectorPatchPieces(i, horizonDeg.size(), patches))
            out[p.patch] += wedgeKFast(normal, p.range, std::max(h, p.lowerRad), p.upperRad);
    }
}

SkyReference referenceSky(const std::function<double(double azimuthDeg)>& horizonDeg,
                          const EnuVector& normal, int azimuthSamples) {
    if (azimuthSamples < 1) throw Error("referenceSky: azimuthSamples must be >= 1");
    const detail::NormalFrame f = detail::makeNormalFrame(detail::unitNormal(normal));
    const double dPhi = 2.0 * kPi / azimuthSamples;
    double piK = 0.0, sin2 = 0.0, sin1 = 0.0, omega = 0.0;
    double ve = 0.0, vn = 0.0, vu = 0.0;
    for (int j = 0; j < azimuthSamples; ++j) {
        const double phi = (j + 0.5) * dPhi;
        const double h = clampElevationRad(horizonDeg(phi / kDegToRad));
        const double hPos = std::max(h, 0.0);
        sin2 += std::sin(hPos) * std::sin(hPos);
        sin1 += std::sin(hPos);
        // Lower limit at this azimuth: the horizon or the tangent plane, whichever is higher.
        const double lo = std::max(h, detail::planeElevation(f, phi));
        const double sPhi = std::sin(phi), cPhi = std::cos(phi);
        const double cos2 = detail::cos2Antiderivative(kHalfPi) - detail::cos2Antiderivative(lo);
        const double sinCos =
            detail::sinCosAntiderivative(kHalfPi) - detail::sinCosAntiderivative(lo);
        piK += (f.east * sPhi + f.north * cPhi) * cos2 + f.up * sinCos;
        omega += 1.0 - std::sin(lo);
        ve += sPhi * cos2;
        vn += cPhi * cos2;
        vu += sinCos;
    }
    SkyReference r;
    r.skyK = piK * dPhi / kPi;
    r.svfHorizontal = 1.0 - sin2 / azimuthSamples;
    r.skyFraction = 1.0 - sin1 / azimuthSamples;
    r.solidAngleSr = omega * dPhi;
    const double len = std::sqrt(ve * ve + vn * vn + vu * vu);
    r.bentNormal = len > 0.0 ? EnuVector{ve / len, vn / len, vu / len} : normal;
    return r;
}

// ---- SkyAccumulator --------------------------------------------------------------------------

SkyAccumulator::SkyAccumulator(const Grid<float>& normalEast, const Grid<float>& normalNorth,
                               const Grid<float>& normalUp, std::size_t directions,
                               SkyPatches patches)
    : east_(normalEast),
      north_(normalNorth),
      up_(normalUp),
      directions_(directions),
      patches_(std::move(patches)),
      added_(directions, false),
      nanOutside_(normalEast.height(), RowSpan{0, normalEast.width()}),
      sumK_(normalEast.width(), normalEast.height(), 0.0f),
      sumSin_(normalEast.width(), normalEast.height(), 0.0f),
      sumSin2_(normalEast.width(), normalEast.height(), 0.0f) {
    checkCellInputs(east_, north_, up_);
    if (directions == 0) throw Error("sky: the number of directions must be at least 1");
    for (std::size_t p = 0; p < patches_.size(); ++p)
        sumPatch_.emplace_back(east_.width(), east_.height(), 0.0f);
}

void SkyAccumulator::addDirection(std::size_t index, const Grid<float>& horizonDeg) {
    addDirection(index, horizonDeg, CellWindow{0, 0, horizonDeg.width(), horizonDeg.height()});
}

void SkyAccumulator::addDirection(std::size_t index, const Grid<float>& horizonDeg, const CellWindow& cells) {
    if (index >= directions_)
        throw Error("sky: direction index " + std::to_string(index) + " out of range 0.." +
                    std::to_string(directions_ - 1));
    if (added_[index])
        throw Error("sky: direction " + std::to_string(index) + " added twice");
    if (cells.col1 - cells.col0 != east_.width() || cells.row1 - cells.row0 != east_.height() ||
        cells.col1 > horizonDeg.width() || cells.row1 > horizonDeg.height() || cells.col0 > cells.col1 ||
        cells.row0 > cells.row1)
        throw Error("sky: horizon grid size differs from the normal grids");
    added_[index] = true;
    const auto [phi1, phi2] = detail::sectorBoundsRad(index, directions_);
    const detail::AzimuthRange sector = detail::makeAzimuthRange(phi1, phi2);
    const std::vector<PatchPiece> pieces = sectorPatchPieces(index, directions_, patches_);
    const std::size_t width = east_.width();
    const FastSector fast = makeFastSector(sector);
    [[maybe_unused]] const bool eightAtOnce =
        fast.narrow && simdPath() == SimdPath::Avx512;
    parallelFor(0, east_.height(), [&](std::size_t row) {
        thread_local std::vector<std::uint8_t> risesBuffer;
        risesBuffer.resize(width);
        std::uint8_t* rises = risesBuffer.data();
        const float* h = horizonDeg.rowPtr(cells.row0 + row) + cells.col0;
        const float* e = east_.rowPtr(row);
        const float* n = north_.rowPtr(row);
        const float* u = up_.rowPtr(row);
        float* k = sumK_.rowPtr(row);
        float* s1 = sumSin_.rowPtr(row);
        float* s2 = sumSin2_.rowPtr(row);
        // A NaN horizon (a nodata cell) makes all three sums NaN whatever else is added (pass 1
        // for s1, s2 and K under a narrow sector or a level plane; pass 2 for K otherwise): the
        // runs of them at the row's ends (a coastal DEM's sea) are set so without computing, and
        // both passes take only the cells between them.
        const auto [c0, c1] = nonNanSpan(h, width);
        if (RowSpan& set = nanOutside_[row]; set.first != c0 || set.end != c1) {
            for (const auto& [from, to] : {std::pair{std::size_t{0}, c0}, std::pair{c1, width}}) {
                std::fill(k + from, k + to, kNaNf);
                std::fill(s1 + from, s1 + to, kNaNf);
                std::fill(s2 + from, s2 + to, kNaNf);
            }
            set = {c0, c1};
        }
        // Pass 1, vectorised: the SVF sums of every cell, and K where the plane stays below.
        accumulateRowFast(h + c0, e + c0, n + c0, u + c0, k + c0, s1 + c0, s2 + c0, rises + c0, c1 - c0, fast);
        // Pass 2: the cells whose tangent plane rises above the horizon somewhere in the sector
        // (about a fifth of the tilted ones on real terrain), exactly in double.
        const auto addExact = [&](std::size_t col) {
            const EnuVector normal = detail::unitNormal({e[col], n[col], u[col]});
            const double hRad = clampElevationRad(h[col]);
            const auto [sinH, cosH] = fastSinCosElevation(hRad);
            const double sectorK =
                fast.narrow ? detail::sectorPiKAboveLower(normal.east, normal.north, normal.up, sector, hRad,
                                                            sinH, cosH) / kPi
                              : wedgeKFast(normal, sector, hRad, sinH, cosH, kHalfPi);
            k[col] += static_cast<float>(sectorK);
        };
#ifdef DEMLIGHT_SKY_LANES
        // Eight such cells at once under a sector narrower than pi (demlight/lighting/sky_wedge_lanes.h: K
        // within a few units in the last place of the double; the same floats in every output
        // compared).
        thread_local std::vector<std::size_t> exactCols;
        exactCols.clear();
#endif
        for (std::size_t col = c0; col < c1; ++col) {
            // Eight flags at a time: most are clear.
            if (std::uint64_t eight; col + 8 <= c1 && (col & 7) == 0 &&
                                     (std::memcpy(&eight, rises + col, 8), eight == 0)) {
                col += 7;
                continue;
            }
            if (!rises[col]) continue;
            if (std::isnan(h[col]) || std::isnan(e[col]) || std::isnan(n[col]) || std::isnan(u[col])) {
                k[col] = kNaNf;
                continue;
            }
#ifdef DEMLIGHT_SKY_LANES
            if (eightAtOnce) {
                exactCols.push_back(col);
                continue;
            }
#endif
            addExact(col);
        }
#ifdef DEMLIGHT_SKY_LANES
        detail::inGroupsOfEight(exactCols, [&](const std::size_t* cols) {
            alignas(64) double le[detail::kSkyLanes], ln[detail::kSkyLanes], lu[detail::kSkyLanes],
                lh[detail::kSkyLanes], lk[detail::kSkyLanes];
            detail::gather8(e, cols, le);
            detail::gather8(n, cols, ln);
            detail::gather8(u, cols, lu);
            detail::gather8(h, cols, lh);
            detail::risingSectorK8(le, ln, lu, lh, sector, lk);
            for (std::size_t l = 0; l < detail::kSkyLanes; ++l) k[cols[l]] += static_cast<float>(lk[l]);
        }, addExact);
#endif
        // Patches: per cell, with the general wedge.
        if (pieces.empty()) return;
        for (std::size_t col = 0; col < width; ++col) {
            if (std::isnan(h[col]) || std::isnan(e[col]) || std::isnan(n[col]) || std::isnan(u[col])) {
                for (std::size_t p = 0; p < patches_.size(); ++p) sumPatch_[p].rowPtr(row)[col] = kNaNf;
                continue;
            }
            const EnuVector normal = detail::unitNormal({e[col], n[col], u[col]});
            const double hRad = clampElevationRad(h[col]);
            const auto [sinH, cosH] = fastSinCosElevation(hRad);
            for (const PatchPiece& p : pieces)
                sumPatch_[p.patch].rowPtr(row)[col] += static_cast<float>(
                    hRad >= p.lowerRad
                        ? wedgeKFast(normal, p.range, hRad, sinH, cosH, p.upperRad)
                        : wedgeKFast(normal, p.range, p.lowerRad, p.upperRad));
        }
    });
}

SkyMaps SkyAccumulator::finish(double albedo) const& {
    SkyMaps maps = copiedSums();
    finishInPlace(maps, nullptr, albedo);
    return maps;
}

SkyMaps SkyAccumulator::finish(const Grid<float>& albedo) const& {
    SkyMaps maps = copiedSums();
    finishInPlace(maps, &albedo, 0.0);
    return maps;
}

SkyMaps SkyAccumulator::finish(double albedo) && {
    SkyMaps maps = movedSums();
    finishInPlace(maps, nullptr, albedo);
    return maps;
}

SkyMaps SkyAccumulator::finish(const Grid<float>& albedo) && {
    SkyMaps maps = movedSums();
    finishInPlace(maps, &albedo, 0.0);
    return maps;
}

SkyMaps SkyAccumulator::copiedSums() const {
    SkyMaps maps;
    maps.svfHorizontal = sumSin2_;
    maps.skyFraction = sumSin_;
    maps.skyK = sumK_;
    maps.patchK = sumPatch_;
    return maps;
}

SkyMaps SkyAccumulator::movedSums() {
    SkyMaps maps;
    maps.svfHorizontal = std::move(sumSin2_);
    maps.skyFraction = std::move(sumSin_);
    maps.skyK = std::move(sumK_);
    maps.patchK = std::move(sumPatch_);
    return maps;
}

void SkyAccumulator::finishInPlace(SkyMaps& maps, const Grid<float>* albedo, double constantAlbedo) const {
    for (std::size_t i = 0; i < directions_; ++i)
        if (!added_[i])
            throw Error("sky: direction " + std::to_string(i) + " of " +
                        std::to_string(directions_) + " was never added");
    if (albedo && !albedo->sameShape(east_)) throw Error("sky: albedo grid size differs from the DEM");
    const std::size_t w = east_.width(), ht = east_.height();
    if (!maps.skyK.sameShape(east_)) throw Error("sky: the accumulator was already finished");
    maps.skyFactor = Grid<float>(w, ht, kNaNf);
    const double d = static_cast<double>(directions_);
    parallelFor(0, ht, [&](std::size_t row) {
        float* svf = maps.svfHorizontal.rowPtr(row);  // holds sum sin^2 h
        float* fraction = maps.skyFraction.rowPtr(row);  // holds sum sin h
        float* skyK = maps.skyK.rowPtr(row);  // holds sum K (tilted cells)
        float* factor = maps.skyFactor.rowPtr(row);
        for (std::size_t col = 0; col < w; ++col) {
            const double sumSin2 = svf[col], sumSin = fraction[col], sumK = skyK[col];
            svf[col] = static_cast<float>(1.0 - sumSin2 / d);
            fraction[col] = static_cast<float>(1.0 - sumSin / d);
            const double nu = up_(col, row);
            const double ec = east_(col, row), nc = north_(col, row);
            const bool flat = ec * ec + nc * nc < detail::kFlatNormalEps * detail::kFlatNormalEps;
            const double unitUp = detail::unitNormal({ec, nc, nu}).up;
            double k = flat ? unitUp * (1.0 - sumSin2 / d) : sumK;
            if (std::isnan(sumK)) k = sumK;
            k = std::clamp(k, 0.0, 1.0);  // rounding of the sector sums (NaN stays NaN)
            skyK[col] = static_cast<float>(k);
            const double c = albedo ? (*albedo)(col, row) : constantAlbedo;
            factor[col] = std::isnan(k) || std::isnan(c) ? kNaNf : static_cast<float>(skyFactor(k, c));
        }
    });
}

SkyMaps computeSky(const std::vector<const Grid<float>*>& horizonsDeg,
                   const Grid<float>& normalEast, const Grid<float>& normalNorth,
                   const Grid<float>& normalUp, double albedo, const SkyPatches& patches) {
    SkyAccumulator acc(normalEast, normalNorth, normalUp, horizonsDeg.size(), patches);
    for (std::size_t i = 0; i < horizonsDeg.size(); ++i) {
        if (!horizonsDeg[i]) throw Error("sky: horizon grid " + std::to_string(i) + " is null");
        acc.addDirection(i, *horizonsDeg[i]);
    }
    return std::move(acc).finish(albedo);
}

}  // namespace demlight
