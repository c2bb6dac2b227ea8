// The upper-hull horizon kernel over a block of parallel lines (Dozier 1981; Timonen & Westerholm
// 2010): walking each line from its first sample, a sample's horizon on the side already walked is
// the steepest sight line to an earlier sample, and that sample is the vertex below the new point
// on the upper convex hull of the earlier ones, once the vertices the new point hides are popped.
//
// The earth's curvature enters as a drop of every height by sigma^2 / (2 R) (sigma: distance along
// the line); the hull of the dropped heights g is the hull of the curved problem, and the tangent
// from the new point at sigma to a vertex at sigma_v is (g_v - g) / (sigma - sigma_v) - sigma / R
// (the drop's two parts, sigma^2 - sigma_v^2 = (sigma - sigma_v)(sigma + sigma_v), cancel into the
// last term exactly).
//
// Three kernels compute it:
// - hullSlopesReference: the exact hull in double precision, one line at a time (pop while the new
//   point does not see the top vertex above the one below it). For tests and error bounds.
// - an AVX-512 kernel in single precision, sixteen lines a vector, without gathers or scatters:
//   each lane keeps the top five vertices of its hull in registers, all four pop tests of the
//   window are evaluated at once and the pops are their leading run; the hull is a linked list
//   through the points (each point's slot holds the row of the vertex below it), so a push is one
//   vector store; a lane that pops its whole window walks the links in scalar code. Distances are
//   integer sample differences times the spacing (plus each sample's small offset from a uniform
//   spacing), so they stay exact where a float distance from the line's start would not; the
//   tangent is one correctly rounded division.
// - hullSlopesPortable: the vector kernel's arithmetic one line at a time in plain float code
//   (the same operations in the same order, the pops a loop over the same test), so it gives the
//   vector kernel's bits on any processor.
// hullSlopes runs the AVX-512 kernel where simdPath() allows it, the portable one elsewhere: the
// same bits either way. The float kernels agree with the reference within hullSlopeErrorBound
// (derived there); tests hold them to it. The lines are a block's
// columns (HullBlock) or lines sheared across a grid, each cell served from the two beside it
// (HullShear); the line geometry of a sweep (which azimuths, regions, transposes) is not here.
#pragma once

#include <cstddef>
#include <vector>

namespace demlight {

/// Where the samples of a set of parallel lines lie along them, the same on every line.
struct HullGeometry {
    /// Distance of sample i from the lines' first sample (metres), increasing, sigmaM[0] = 0.
    std::vector<double> sigmaM;
    /// 1 / effective earth radius (1/m), refraction included; 0 for a flat earth.
    double invRadius = 0.0;
    /// Empty (every line's samples at sigmaM), or one factor per line of a HullBlock: line b's
    /// sample i lies at sigmaM[i] * lineScale[b], for lines whose spacing differs from line to
    /// line but not along them (rows of a geographic grid, each walked at its own cell width).
    /// With factors sigmaM must be uniform (sigmaM[i] = i * sigmaM[1] up to float rounding).
    std::vector<double> lineScale;
    /// The uniform spacing the float kernels count distances in (each sample's offset from
    /// i * spacingM is kept apart); 0: sigmaM's mean step. Give it where the first samples of
    /// lines of different lengths must round alike (a window's walk and its DEM's).
    double spacingM = 0.0;
};

/// A block of lines in a row-major array: sample i of line b is at heightsM[i * stride + b] (metres,
/// NaN nodata), and its slope is written to out[i * stride + b]. lines <= stride.
struct HullBlock {
    const float* heightsM = nullptr;
    float* out = nullptr;
    std::size_t stride = 0;
    std::size_t lines = 0;
    /// Where the samples of the heights and of the output follow each other when not `stride`
    /// apart (0: stride), in floats; negative walks a grid's rows upward.
    std::ptrdiff_t heightsRowStep = 0, outRowStep = 0;
    /// Samples before this one are walked (pushed onto the hulls) but their slopes not written.
    std::size_t firstOutRow = 0;
};

/// Reusable scratch of the kernels (grows to what a block needs, never shrinks).
struct HullScratch {
    std::vector<double> hullD;
    std::vector<float> pointG, pointLink, rowTables, lineHull;
};

/// The horizon slope (tangent of the elevation angle, curvature included) of every sample of the
/// block's lines towards their first sample: -inf where no earlier sample has data, NaN at nodata.
/// Runs the vector kernel where simdPath() allows it (AVX-512), the portable float kernel
/// elsewhere (the same bits).
void hullSlopes(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch);

/// The exact hull in double precision (tests, error bounds).
void hullSlopesReference(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch);

/// The vector kernel's float arithmetic one line at a time, in code for any processor: its bits.
void hullSlopesPortable(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch);

/// Whether this build and processor run the vector kernel (and hullSlopesVector may be called).
bool hullVectorKernelAvailable();

/// The AVX-512 kernel, whatever simdPath() says (for tests and benchmarks); throws Error where
/// hullVectorKernelAvailable() is false.
void hullSlopesVector(const HullGeometry& geometry, const HullBlock& block, HullScratch& scratch);

/// Parallel lines crossing a grid at a shear: line m passes row r at column m + r * shearCols
/// (cell centres at integers; 0 <= shearCols <= 1, lines within 45 degrees of the columns), its
/// height there interpolated between the two cells beside it, its samples one a row (distance
/// geometry.sigmaM[r] from row 0 along the line). The horizon slope of each cell is served from the
/// two lines beside it, linearly in their distance across (-inf where either has no earlier
/// sample, NaN at nodata and where either line's sample has none). The lines that matter start on
/// the grid's top or left edge and end on its bottom or right edge.
struct HullShear {
    const float* heightsM = nullptr;  // row-major, width * height, NaN nodata
    float* out = nullptr;             // width * height slopes
    std::size_t width = 0, height = 0;
    double shearCols = 0.0;
};

/// The served slopes of every cell, the lines through hullSlopesReference.
void hullShearReference(const HullGeometry& geometry, const HullShear& grid, HullScratch& scratch);

/// The same with the vector kernel, sixteen adjacent lines a group: a row's heights of a group
/// are two unaligned loads and one multiply-add (the lines share the fraction across), fifteen
/// cells are served from the group's slopes shifted by one lane; throws Error where
/// hullVectorKernelAvailable() is false.
void hullShearVector(const HullGeometry& geometry, const HullShear& grid, HullScratch& scratch);

/// A bound on |slope(vector kernel) - slope(reference)|: absolute + relative * |slope(reference)|.
struct HullSlopeBound {
    double absolute = 0.0, relative = 0.0;
    double at(double slopeRef) const { return absolute + relative * (slopeRef < 0 ? -slopeRef : slopeRef); }
};

/// The bound for lines whose heights, drops sigma^2 / (2 R) and dropped heights g stay below
/// maxAbsGM in magnitude (metres). With u_G one float ulp at maxAbsGM and d_min the smallest
/// distance between samples:
/// - the float kernels round each g to float (the drop and the difference, half an ulp each; with
///   per-line factors the drop is r^2 times a rounded factor, one ulp more) and the rise g_v - g
///   once more: a slope to any earlier sample moves by at most 3 u_G / d_min (4 u_G), so
///   the hull's maximum moves by no more; the pop tests' own rounding only swaps vertices whose
///   slopes lie as close, which at most doubles it;
/// - a distance is exact in samples, times the spacing (one rounding) plus the difference of two
///   offsets from the uniform spacing (one ulp of the largest offset, over d_min), and the
///   division and the subtraction of sigma / R add a few float roundings: together under
///   2^-20 + 2 ulp(offset) / d_min of |slope| + 2 sigma_max / R (sigma_max of the longest line).
/// The whole doubled for margin.
HullSlopeBound hullSlopeErrorBound(const HullGeometry& geometry, double maxAbsGM);

}  // namespace demlight
