// A bitmap of a terrain's valid cells per scan orientation, so that a block of lines skips
// steps that meet only nodata (a coastal tile's sea) without reading their heights.
#pragma once

#include "demlight/lighting/horizon.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace demlight::sweep {

/// A word with its n lowest bits set (all 64 for n >= 64).
inline std::uint64_t lowBits(std::size_t n) { return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1; }

/// Bit j % 64 of out[m] for the cells m of a row (X-major lines: minor index j is the row).
inline void setRowBits(std::uint64_t* __restrict out, const float* __restrict row, std::size_t width, unsigned bit) {
    for (std::size_t m = 0; m < width; ++m) out[m] |= static_cast<std::uint64_t>(row[m] == row[m]) << bit;
}

/// Bits 0..n-1 for cells 0..n-1 of a run along a row (Y-major lines: minor index j is the column).
inline std::uint64_t rowRunBits(const float* __restrict row, std::size_t n) {
    std::uint64_t w = 0;
    for (std::size_t j = 0; j < n; ++j) w |= static_cast<std::uint64_t>(row[j] == row[j]) << j;
    return w;
}

/// Which of a terrain's cells hold a height, one bit each, laid out along one scan orientation:
/// the cells a block of lines meets at one step (one major index, consecutive minor indices) are
/// one or two words, where the heights are a cell a row apart (X-major lines: a column). Half
/// of a coastal tile is sea: its steps are told by this test, without reading their heights.
/// Bit (m, j) is at words[(j / 64) * majorSize + m] (a step's words next to the next step's);
/// no words where few cells are nodata (kBitmapVoidShare). Indices are the terrain's (major -
/// majorLo, minor - minorLo).
class ValidCells {
public:
    /// The bitmap of `bits`, built first unless it is this terrain's heights grid's.
    ValidCells(const Terrain& t, bool xMajor, SweepBuffers::ValidBits& bits)
        : majorSize_(xMajor ? t.width() : t.height()) {
        if (bits.heights != t.heightsM.data() || bits.width != t.width() || bits.height != t.height()) {
            build(t, xMajor, bits.words);
            bits.heights = t.heightsM.data();
            bits.width = t.width();
            bits.height = t.height();
        }
        words_ = bits.words.empty() ? nullptr : bits.words.data();
    }
    /// Whether the bitmap is kept: see kBitmapVoidShare.
    bool used() const { return words_ != nullptr; }
    /// Whether any of cells j0..j1 (inclusive, 0 <= j0 <= j1) at major index m holds a height;
    /// only when used().
    bool any(long m, long j0, long j1) const {
        const auto at = [&](long j) {
            return words_[static_cast<std::size_t>(j) / 64 * majorSize_ + static_cast<std::size_t>(m)];
        };
        const long w0 = j0 / 64, w1 = j1 / 64;
        if (w0 == w1) return (at(j0) >> (j0 % 64)) & lowBits(static_cast<std::size_t>(j1 - j0 + 1));
        if (at(j0) >> (j0 % 64)) return true;
        for (long w = w0 + 1; w < w1; ++w)
            if (at(w * 64)) return true;
        return at(j1) & lowBits(static_cast<std::size_t>(j1 % 64 + 1));
    }

private:
    /// The bitmap is kept where at least this share of the cells is nodata: where voids are few
    /// and scattered, few steps of a block meet only nodata, and its extra tests (serving,
    /// prefetching) cost more than they skip (measured: docs/performance.md, "Sea and other
    /// large voids skipped"). Below it the sweep reads a step's heights until it finds one.
    static constexpr double kBitmapVoidShare = 0.1;

    void build(const Terrain& t, bool xMajor, std::vector<std::uint64_t>& words) const {
        const std::size_t W = t.width(), H = t.height();
        const std::size_t minorSize = xMajor ? H : W, groups = (minorSize + 63) / 64;
        words.assign(groups * majorSize_, 0);
        std::atomic<std::size_t> validCells{0};
        parallelFor(0, groups, [&](std::size_t g) {
            std::uint64_t* out = words.data() + g * majorSize_;
            const std::size_t j0 = g * 64, n = std::min<std::size_t>(64, minorSize - j0);
            if (xMajor) {
                for (std::size_t j = j0; j < j0 + n; ++j) setRowBits(out, t.heightsM.rowPtr(j), W, static_cast<unsigned>(j % 64));
            } else {
                for (std::size_t m = 0; m < H; ++m) out[m] = rowRunBits(t.heightsM.rowPtr(m) + j0, n);
            }
            std::size_t count = 0;
            for (std::size_t m = 0; m < majorSize_; ++m) count += static_cast<std::size_t>(std::popcount(out[m]));
            validCells += count;
        });
        const double voids = static_cast<double>(W * H - validCells.load());
        if (voids < kBitmapVoidShare * static_cast<double>(W * H)) words.clear();
    }

    std::size_t majorSize_;
    const std::uint64_t* words_ = nullptr;
};

}  // namespace demlight::sweep
