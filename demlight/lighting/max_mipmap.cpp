#include "demlight/lighting/max_mipmap.h"

#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace demlight {
namespace {

constexpr float kHole = -std::numeric_limits<float>::infinity();
/// Most steps of one ray: a guard against a loop that stops advancing (never reached by a ray
/// that does: each step leaves a node).
constexpr std::size_t kMaxSteps = std::size_t{1} << 26;

/// [tIn, tOut] of the ray inside lo <= p + t d <= hi along one axis; empty when tIn > tOut.
void clipSlab(double p, double d, double lo, double hi, double& tIn, double& tOut) {
    if (d == 0) {
        if (p < lo || p > hi) tIn = std::numeric_limits<double>::infinity();
        return;
    }
    double t0 = (lo - p) / d, t1 = (hi - p) / d;
    if (t0 > t1) std::swap(t0, t1);
    tIn = std::max(tIn, t0);
    tOut = std::min(tOut, t1);
}

/// The node (at a level of 2^k patches per node) holding the point at coordinate x, going in
/// direction d: a point on a boundary belongs to the node the ray goes into.
std::size_t nodeIndex(double x, double d, int k, std::size_t nodes) {
    const double xs = std::ldexp(x, -k);
    const double i = d >= 0 ? std::floor(xs) : std::ceil(xs) - 1;
    return static_cast<std::size_t>(std::clamp(i, 0.0, static_cast<double>(nodes - 1)));
}

/// The parameter where the ray leaves [lo, hi] along an axis (infinity when parallel to it).
double exitAlong(double p, double d, double lo, double hi) {
    if (d > 0) return (hi - p) / d;
    if (d < 0) return (lo - p) / d;
    return std::numeric_limits<double>::infinity();
}

GridHit hitAt(const GridRay& r, double t) { return {t, r.x + r.dx * t, r.y + r.dy * t, r.z + r.dz * t}; }

}  // namespace

MaxMipmap::MaxMipmap(const Grid<float>& heights) : heights_(&heights) {
    if (heights.width() < 2 || heights.height() < 2)
        throw Error("a height field to ray-cast needs at least 2 x 2 cells (it has " + std::to_string(heights.width()) +
                    " x " + std::to_string(heights.height()) + ")");
    const std::size_t pw = heights.width() - 1, ph = heights.height() - 1;
    Grid<float> base(pw, ph);
    parallelFor(0, ph, [&](std::size_t j) {
        for (std::size_t i = 0; i < pw; ++i) {
            const float a = heights(i, j), b = heights(i + 1, j), c = heights(i, j + 1), d = heights(i + 1, j + 1);
            base(i, j) = std::isnan(a) || std::isnan(b) || std::isnan(c) || std::isnan(d) ? kHole
                                                                                          : std::max({a, b, c, d});
        }
    }, 16);
    levels_.push_back(std::move(base));
    while (levels_.back().width() > 1 || levels_.back().height() > 1) {
        const Grid<float>& below = levels_.back();
        Grid<float> up((below.width() + 1) / 2, (below.height() + 1) / 2);
        parallelFor(0, up.height(), [&](std::size_t j) {
            for (std::size_t i = 0; i < up.width(); ++i) {
                float m = kHole;
                for (std::size_t y = 2 * j; y < std::min(2 * j + 2, below.height()); ++y)
                    for (std::size_t x = 2 * i; x < std::min(2 * i + 2, below.width()); ++x) m = std::max(m, below(x, y));
                up(i, j) = m;
            }
        }, 16);
        levels_.push_back(std::move(up));
    }
}

std::optional<double> intersectPatch(const Grid<float>& h, std::size_t i, std::size_t j, const GridRay& ray, double s0,
                                     double s1) {
    // Tevs et al. 3.3: with the ray written from its point at s0 (for precision far from the
    // origin), f(s) = z(s) - H(u(s), v(s)) = c + b s + a s^2 on the patch's own coordinates u, v.
    const double h00 = h(i, j), h10 = h(i + 1, j), h01 = h(i, j + 1), h11 = h(i + 1, j + 1);
    const double A = h10 - h00, B = h01 - h00, C = h00 - h10 - h01 + h11;
    const double u0 = ray.x + ray.dx * s0 - static_cast<double>(i), v0 = ray.y + ray.dy * s0 - static_cast<double>(j);
    const double z0 = ray.z + ray.dz * s0;
    const double c = z0 - (h00 + A * u0 + B * v0 + C * u0 * v0);
    const double b = ray.dz - (A * ray.dx + B * ray.dy + C * (u0 * ray.dy + v0 * ray.dx));
    const double a = -C * ray.dx * ray.dy;
    const double len = s1 - s0;
    // Under the surface where it enters (it came through a hole or the field's side): the ray
    // meets the surface only from above, so it sees through walls it is behind.
    if (c <= 0) return std::nullopt;
    const auto f = [&](double s) { return c + s * (b + s * a); };
    double first = std::numeric_limits<double>::infinity();
    const double scale = std::abs(b) + std::abs(a) * len;
    if (std::abs(a) * len <= 1e-12 * (scale + 1e-300)) {
        if (b < 0) first = -c / b;
    } else {
        const double disc = b * b - 4 * a * c;
        if (disc >= 0) {
            // The stable pair of roots (Numerical Recipes 5.6).
            const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
            const double r1 = q / a, r2 = q != 0 ? c / q : r1;
            for (double r : {r1, r2})
                if (r >= 0 && r < first) first = r;
        }
    }
    if (first <= len) return s0 + first;
    if (f(len) <= 0) return s1;  // a root rounded just past the patch's end
    return std::nullopt;
}

std::optional<GridHit> MaxMipmap::cast(const GridRay& ray, double tMax) const {
    const Grid<float>& h = *heights_;
    const double xHi = static_cast<double>(h.width() - 1), yHi = static_cast<double>(h.height() - 1);
    double t = 0, tOut = tMax;
    clipSlab(ray.x, ray.dx, 0, xHi, t, tOut);
    clipSlab(ray.y, ray.dy, 0, yHi, t, tOut);
    // Above the highest point and not coming down: nothing to meet.
    const double zTop = top();
    if (ray.z + ray.dz * t > zTop) {
        if (ray.dz >= 0) return std::nullopt;
        t = std::max(t, (zTop - ray.z) / ray.dz);
    }
    const int topLevel = static_cast<int>(levels_.size()) - 1;
    int k = topLevel;
    for (std::size_t step = 0; t < tOut && step < kMaxSteps; ++step) {
        const Grid<float>& level = levels_[static_cast<std::size_t>(k)];
        const double x = ray.x + ray.dx * t, y = ray.y + ray.dy * t;
        const std::size_t a = nodeIndex(x, ray.dx, k, level.width()), b = nodeIndex(y, ray.dy, k, level.height());
        const double size = std::ldexp(1.0, k);
        const double x0 = static_cast<double>(a) * size, y0 = static_cast<double>(b) * size;
        double tExit = std::min({tOut, exitAlong(ray.x, ray.dx, x0, std::min(x0 + size, xHi)),
                                 exitAlong(ray.y, ray.dy, y0, std::min(y0 + size, yHi))});
        if (tExit <= t) tExit = std::min(tOut, t + 1e-9 * (1.0 + std::abs(t)));  // on a corner: step past it
        const double zMax = level(a, b);
        const double zLow = std::min(ray.z + ray.dz * t, ray.z + ray.dz * tExit);
        if (zLow > zMax) {  // the ray passes over the whole node
            t = tExit;
            k = std::min(k + 1, topLevel);
            continue;
        }
        if (k > 0) {
            --k;
            continue;
        }
        if (const auto s = intersectPatch(h, a, b, ray, t, tExit)) return hitAt(ray, *s);
        t = tExit;
        k = std::min(1, topLevel);
    }
    return std::nullopt;
}

std::optional<GridHit> castRayThroughEveryPatch(const Grid<float>& h, const GridRay& ray, double tMax) {
    if (h.width() < 2 || h.height() < 2) return std::nullopt;
    const std::size_t pw = h.width() - 1, ph = h.height() - 1;
    double t = 0, tOut = tMax;
    clipSlab(ray.x, ray.dx, 0, static_cast<double>(pw), t, tOut);
    clipSlab(ray.y, ray.dy, 0, static_cast<double>(ph), t, tOut);
    for (std::size_t step = 0; t < tOut && step < kMaxSteps; ++step) {
        const double x = ray.x + ray.dx * t, y = ray.y + ray.dy * t;
        const std::size_t i = nodeIndex(x, ray.dx, 0, pw), j = nodeIndex(y, ray.dy, 0, ph);
        const double xi = static_cast<double>(i), yj = static_cast<double>(j);
        double tExit = std::min({tOut, exitAlong(ray.x, ray.dx, xi, xi + 1), exitAlong(ray.y, ray.dy, yj, yj + 1)});
        if (tExit <= t) tExit = std::min(tOut, t + 1e-9 * (1.0 + std::abs(t)));
        const bool solid = !std::isnan(h(i, j)) && !std::isnan(h(i + 1, j)) && !std::isnan(h(i, j + 1)) &&
                           !std::isnan(h(i + 1, j + 1));
        if (solid)
            if (const auto s = intersectPatch(h, i, j, ray, t, tExit)) return hitAt(ray, *s);
        t = tExit;
    }
    return std::nullopt;
}

}  // namespace demlight
