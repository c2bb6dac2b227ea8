// Grid<T>: an owning, row-major 2-D array.
//
// Layout: element (col, row) lives at offset row * width + col; row 0 is the NORTH (top) row of a
// north-up raster, as in GDAL. Cell-centre convention: cell (col, row) covers the pixel square
// whose centre is at pixel coordinates (col + 0.5, row + 0.5) of the geotransform.
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

namespace demlight {

template <class T>
class Grid {
public:
    Grid() = default;
    Grid(std::size_t width, std::size_t height, T fill = T{})
        : width_(width), height_(height), data_(width * height, fill) {}

    std::size_t width() const { return width_; }
    std::size_t height() const { return height_; }
    std::size_t size() const { return data_.size(); }
    bool empty() const { return data_.empty(); }

    T& operator()(std::size_t col, std::size_t row) {
        assert(col < width_ && row < height_);
        return data_[row * width_ + col];
    }
    const T& operator()(std::size_t col, std::size_t row) const {
        assert(col < width_ && row < height_);
        return data_[row * width_ + col];
    }
    T* rowPtr(std::size_t row) { return data_.data() + row * width_; }
    const T* rowPtr(std::size_t row) const { return data_.data() + row * width_; }

    T* data() { return data_.data(); }
    const T* data() const { return data_.data(); }
    std::vector<T>& values() { return data_; }
    const std::vector<T>& values() const { return data_; }

    bool sameShape(const Grid& other) const {
        return width_ == other.width_ && height_ == other.height_;
    }

private:
    std::size_t width_ = 0;
    std::size_t height_ = 0;
    std::vector<T> data_;
};

/// A half-open window of cells of the global grid: columns [col0, col1), rows [row0, row1).
struct CellWindow {
    std::size_t col0 = 0, row0 = 0, col1 = 0, row1 = 0;
};

/// One cell (column, row).
struct CellIndex {
    std::size_t col = 0, row = 0;
};

/// The cells [first, last + 1) of a row of n values between its runs of NaN (nodata) at both
/// ends, which the passes over a coastal DEM's rows leave out (its sea); empty where all are NaN.
struct RowSpan {
    std::size_t first = 0, end = 0;
};
inline RowSpan nonNanSpan(const float* row, std::size_t n) {
    // Sixteen values a step while all of them are NaN (a fixed-length test the compiler turns
    // into vector compares: a coastal row's sea is thousands of cells), then one at a time.
    constexpr std::size_t kChunk = 16;
    const auto allNan = [row](std::size_t at) {
        bool all = true;
        for (std::size_t k = 0; k < kChunk; ++k) all &= row[at + k] != row[at + k];
        return all;
    };
    std::size_t first = 0, end = n;
    while (end - first >= kChunk && allNan(first)) first += kChunk;
    while (first < end && row[first] != row[first]) ++first;
    while (end - first >= kChunk && allNan(end - kChunk)) end -= kChunk;
    while (end > first && row[end - 1] != row[end - 1]) --end;
    return {first, end};
}

/// A grid whose every cell is +0 or NaN of one bit pattern (a frame with the sun down): a bitmap
/// of its NaN cells (bit i % 64 of word i / 64) and that pattern. Two such grids of one shape hold
/// the same bits exactly when these are equal.
struct DarkCells {
    std::vector<std::uint64_t> nan;
    std::uint32_t nanBits = 0;
    bool operator==(const DarkCells&) const = default;
};

/// The DarkCells of n values, or none when one holds anything else (a lit cell, most often among
/// the first, ends the search for the NaN pattern at once; then 64 cells a word, without branches
/// inside the word).
inline std::optional<DarkCells> darkCells(const float* v, std::size_t n) {
    const auto bitsAt = [v](std::size_t i) {
        std::uint32_t bits;
        std::memcpy(&bits, v + i, sizeof bits);
        return bits;
    };
    DarkCells d;
    std::size_t i = 0;
    while (i < n && bitsAt(i) == 0) ++i;
    if (i < n) {
        if (v[i] == v[i]) return std::nullopt;  // not NaN
        d.nanBits = bitsAt(i);
    }
    d.nan.assign((n + 63) / 64, 0);
    for (std::size_t w = 0; w < d.nan.size(); ++w) {
        const std::size_t i0 = w * 64, count = std::min<std::size_t>(64, n - i0);
        std::uint64_t word = 0;
        bool other = false;
        for (std::size_t k = 0; k < count; ++k) {
            const std::uint32_t bits = bitsAt(i0 + k);
            other |= bits != 0 && bits != d.nanBits;
            word |= static_cast<std::uint64_t>(bits != 0) << k;
        }
        if (other) return std::nullopt;
        d.nan[w] = word;
    }
    return d;
}

/// The window's cells of a grid as a grid of their own; an empty grid stays empty.
template <class T>
Grid<T> cropGrid(const Grid<T>& g, const CellWindow& w) {
    if (g.empty()) return {};
    Grid<T> out(w.col1 - w.col0, w.row1 - w.row0);
    for (std::size_t r = 0; r < out.height(); ++r)
        std::copy_n(&g(w.col0, w.row0 + r), out.width(), &out(0, r));
    return out;
}

}  // namespace demlight
