#include "demlight/products/quicklook.h"

#include "demlight/geo/image_out.h"
#include "demlight/products/product.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace demlight {
namespace {

/// viridis (van der Walt & Smith, matplotlib's default colour map, CC0) at nine evenly spaced
/// points, as R's viridisLite::viridis(9) lists it; colours between are interpolated linearly.
constexpr std::array<std::array<std::uint8_t, 3>, 9> kViridis9 = {{
    {0x44, 0x01, 0x54}, {0x47, 0x2D, 0x7B}, {0x3B, 0x52, 0x8B}, {0x2C, 0x72, 0x8E}, {0x21, 0x90, 0x8C},
    {0x27, 0xAD, 0x81}, {0x5D, 0xC8, 0x63}, {0xAA, 0xDC, 0x32}, {0xFD, 0xE7, 0x25},
}};

constexpr std::array<std::uint8_t, 4> kInk{40, 40, 40, 255};
constexpr std::array<std::uint8_t, 4> kPaper{255, 255, 255, 255};
constexpr int kTitlePx = 18, kLabelPx = 14, kMarginPx = 12, kBarWidthPx = 22, kTickPx = 5;

/// A value for a tick label: as few digits as tell the ticks apart.
std::string formatTick(double v, double step) {
    const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << (std::abs(v) < step * 1e-9 ? 0.0 : v);
    return s.str();
}

/// The unit for the bar: the band's GDAL unit, cut before an explanation in parentheses.
std::string unitLabel(const PictureBand& band) {
    std::string u = band.unit;
    if (const std::size_t paren = u.find(" ("); paren != std::string::npos) u.resize(paren);
    return u;
}

void fill(Image8& image, std::size_t x0, std::size_t y0, std::size_t w, std::size_t h,
          const std::array<std::uint8_t, 4>& rgba) {
    for (std::size_t y = y0; y < std::min(image.height, y0 + h); ++y)
        for (std::size_t x = x0; x < std::min(image.width, x0 + w); ++x)
            std::copy(rgba.begin(), rgba.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>((y * image.width + x) * 4));
}

}  // namespace

std::array<std::uint8_t, 3> viridis(double t) {
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    const double at = t * (kViridis9.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(at), kViridis9.size() - 2);
    const double f = at - static_cast<double>(i);
    std::array<std::uint8_t, 3> out{};
    for (std::size_t c = 0; c < 3; ++c)
        out[c] = static_cast<std::uint8_t>(std::lround((1 - f) * kViridis9[i][c] + f * kViridis9[i + 1][c]));
    return out;
}

std::optional<std::pair<double, double>> quantileRange(const Grid<float>& values, double low, double high) {
    std::vector<float> finite;
    finite.reserve(values.size());
    for (float v : values.values())
        if (std::isfinite(v)) finite.push_back(v);
    if (finite.empty()) return std::nullopt;
    const auto at = [&](double q) {
        const auto k = static_cast<std::size_t>(std::lround(q * static_cast<double>(finite.size() - 1)));
        std::nth_element(finite.begin(), finite.begin() + static_cast<std::ptrdiff_t>(k), finite.end());
        return static_cast<double>(finite[k]);
    };
    const double lo = at(low);
    return std::pair{lo, at(high)};
}

std::vector<double> niceTicks(double low, double high, int count) {
    std::vector<double> ticks;
    if (!(high > low) || count < 2) return {low};
    const double raw = (high - low) / count;
    const double decade = std::pow(10.0, std::floor(std::log10(raw)));
    double step = decade;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * decade >= raw) {
            step = m * decade;
            break;
        }
    // Fewer than three ticks inside: a finer step.
    for (int tries = 0; tries < 3; ++tries) {
        ticks.clear();
        for (double k = std::ceil(low / step - 1e-9); k * step <= high + step * 1e-9; k += 1) ticks.push_back(k * step);
        if (ticks.size() >= 3) break;
        step /= 2;
    }
    return ticks;
}

Image8 colourBand(const Grid<float>& values, double low, double high, std::size_t width, std::size_t height) {
    Image8 out;
    out.width = width;
    out.height = height;
    out.rgba.assign(width * height * 4, 0);
    const double sx = static_cast<double>(values.width()) / static_cast<double>(width);
    const double sy = static_cast<double>(values.height()) / static_cast<double>(height);
    const double span = high > low ? high - low : 1.0;
    for (std::size_t y = 0; y < height; ++y)
        for (std::size_t x = 0; x < width; ++x) {
            // The cells under the pixel's footprint, or the one under its centre.
            std::size_t c0 = static_cast<std::size_t>(static_cast<double>(x) * sx);
            std::size_t r0 = static_cast<std::size_t>(static_cast<double>(y) * sy);
            std::size_t c1 = std::max(c0 + 1, static_cast<std::size_t>(std::ceil(static_cast<double>(x + 1) * sx)));
            std::size_t r1 = std::max(r0 + 1, static_cast<std::size_t>(std::ceil(static_cast<double>(y + 1) * sy)));
            if (sx < 1) c0 = std::min(values.width() - 1, static_cast<std::size_t>((static_cast<double>(x) + 0.5) * sx)), c1 = c0 + 1;
            if (sy < 1) r0 = std::min(values.height() - 1, static_cast<std::size_t>((static_cast<double>(y) + 0.5) * sy)), r1 = r0 + 1;
            double sum = 0;
            std::size_t n = 0;
            for (std::size_t r = r0; r < std::min(r1, values.height()); ++r)
                for (std::size_t c = c0; c < std::min(c1, values.width()); ++c)
                    if (const float v = values(c, r); std::isfinite(v)) sum += v, ++n;
            std::uint8_t* p = out.rgba.data() + (y * width + x) * 4;
            if (n == 0) {
                p[0] = p[1] = p[2] = kNodataGrey;
                continue;
            }
            const auto rgb = viridis((sum / static_cast<double>(n) - low) / span);
            std::copy(rgb.begin(), rgb.end(), p);
            p[3] = 255;
        }
    return out;
}

std::string quicklookTitle(const PictureBand& band, const std::string& path) {
    const auto item = [&](const char* key) {
        const auto it = band.metadata.find(key);
        return it == band.metadata.end() ? std::string() : it->second;
    };
    std::string title = item("DEMLIGHT_PRODUCT");
    if (title.empty()) title = std::filesystem::path(path).filename().string();
    title += ": " + (band.description.empty() ? "band " + std::to_string(band.index) : band.description);
    // A period's ends at local midnight read as dates.
    const auto day = [](std::string s) {
        if (const std::size_t at = s.find("T00:00:00"); at != std::string::npos) s.resize(at);
        return s;
    };
    std::string when = item("DEMLIGHT_TIME_LOCAL");
    if (when.empty() && !item("DEMLIGHT_START").empty())
        when = day(item("DEMLIGHT_START")) + " to " + day(item("DEMLIGHT_END"));
    if (when.empty() && !item("DEMLIGHT_FIRST_DATE").empty()) {
        when = item("DEMLIGHT_FIRST_DATE");
        if (item("DEMLIGHT_LAST_DATE") != when) when += " to " + item("DEMLIGHT_LAST_DATE");
    }
    return when.empty() ? title : title + ", " + when;
}

QuicklookResult quicklookProduct(const QuicklookRequest& request) {
    if (request.mapSize < 16 || request.mapSize > 16384)
        throw FieldError("mapSize", " " + std::to_string(request.mapSize) + ": must be in [16, 16384]");
    if (request.range && !(std::isfinite(request.range->first) && std::isfinite(request.range->second) &&
                           request.range->first < request.range->second))
        throw FieldError("range", " " + formatNumber(request.range->first) + ", " + formatNumber(request.range->second) +
                                      ": must be two finite values, low < high");
    QuicklookResult out;
    out.band = readPictureBand(request.path, request.band);
    const PictureBand& band = out.band;
    if (band.values.empty()) throw Error("'" + request.path + "' has an empty band " + std::to_string(band.index));
    if (request.range) {
        std::tie(out.low, out.high) = *request.range;
    } else {
        const auto q = quantileRange(band.values, 0.01, 0.99);
        if (!q) throw Error("band " + std::to_string(band.index) + " of '" + request.path + "' holds no value (all nodata)");
        std::tie(out.low, out.high) = *q;
        if (!(out.high > out.low)) out.low -= 0.5, out.high += 0.5;  // a constant band: its value mid-bar
    }

    // Square ground pixels: a latitude/longitude cell is cos(latitude) as wide as it is high.
    const auto& gt = band.geoTransform;
    double groundW = static_cast<double>(band.values.width()) * std::abs(gt[1]);
    const double groundH = static_cast<double>(band.values.height()) * std::abs(gt[5]);
    if (band.geographic) {
        const double midLatDeg = gt[3] + gt[5] * 0.5 * static_cast<double>(band.values.height());
        groundW *= std::cos(std::clamp(midLatDeg, -89.0, 89.0) * M_PI / 180.0);
    }
    const double longer = std::max(groundW, groundH);
    const auto side = [&](double ground) {
        return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(ground / longer * static_cast<double>(request.mapSize))));
    };
    out.mapWidth = side(groundW);
    out.mapHeight = side(groundH);
    const Image8 map = colourBand(band.values, out.low, out.high, out.mapWidth, out.mapHeight);

    // Layout: title above; the map; to its right the bar, its ticks and labels, the unit above it.
    out.title = request.title.empty() ? quicklookTitle(band, request.path) : request.title;
    out.unitLabel = unitLabel(band);
    const std::vector<double> ticks = niceTicks(out.low, out.high, 5);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : std::max(std::abs(out.high - out.low), 1e-6);
    int labelWidth = 0;
    for (double t : ticks) labelWidth = std::max(labelWidth, measureText(formatTick(t, step), kLabelPx).width());
    const TextBox titleBox = measureText(out.title, kTitlePx);
    const TextBox unitBox = measureText(out.unitLabel.empty() ? " " : out.unitLabel, kLabelPx);
    const int titleHeight = kTitlePx + 2 * kMarginPx / 2 + kLabelPx + kMarginPx / 2;  // title, then the unit's line
    out.mapX = kMarginPx;
    out.mapY = static_cast<std::size_t>(kMarginPx + titleHeight);
    const std::size_t barX = out.mapX + out.mapWidth + kMarginPx * 2;
    const std::size_t right = barX + kBarWidthPx + kTickPx + 4 + static_cast<std::size_t>(labelWidth) + kMarginPx;
    Image8& image = out.image;
    image.width = std::max({right, static_cast<std::size_t>(2 * kMarginPx + titleBox.width()),
                            barX + static_cast<std::size_t>(unitBox.width()) + kMarginPx});
    image.height = out.mapY + out.mapHeight + kMarginPx + kLabelPx / 2;
    image.rgba.assign(image.width * image.height * 4, 0);
    fill(image, 0, 0, image.width, image.height, kPaper);
    for (std::size_t y = 0; y < map.height; ++y)
        std::copy_n(map.rgba.begin() + static_cast<std::ptrdiff_t>(y * map.width * 4), map.width * 4,
                    image.rgba.begin() + static_cast<std::ptrdiff_t>(((out.mapY + y) * image.width + out.mapX) * 4));

    // The bar: the map's height, high values at the top.
    const std::size_t barH = out.mapHeight;
    for (std::size_t y = 0; y < barH; ++y) {
        const auto rgb = viridis(1.0 - (static_cast<double>(y) + 0.5) / static_cast<double>(barH));
        fill(image, barX, out.mapY + y, kBarWidthPx, 1, {rgb[0], rgb[1], rgb[2], 255});
    }
    const double span = out.high - out.low;
    for (double t : ticks) {
        const double f = (t - out.low) / span;
        const auto y = static_cast<std::size_t>(std::lround(static_cast<double>(out.mapY) + (1.0 - f) * static_cast<double>(barH - 1)));
        fill(image, barX + kBarWidthPx, y, kTickPx, 1, kInk);
        drawText(image, static_cast<int>(barX + kBarWidthPx + kTickPx + 3), static_cast<int>(y) + kLabelPx / 2 - 2,
                 formatTick(t, step), kLabelPx, kInk);
    }
    drawText(image, kMarginPx, kMarginPx + kTitlePx - 4, out.title, kTitlePx, kInk);
    if (!out.unitLabel.empty())
        drawText(image, static_cast<int>(barX), static_cast<int>(out.mapY) - kMarginPx / 2 - 2, out.unitLabel, kLabelPx, kInk);
    image.text = {{"Title", out.title}, {"Source", request.path}};
    return out;
}

}  // namespace demlight
