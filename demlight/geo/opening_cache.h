// What DemSource::open's pass over a DEM's heights learns (height range, valid count and mean,
// the share of steep steps), kept in a small file so that later processes opening the same DEM
// skip the pass: the processes of a job array, each lighting a --srcwin window of one large DEM,
// would otherwise each read the whole DEM first. The file is keyed to the DEM's path, the height
// options and the size and modification time of every file GDAL reads for it (a VRT's sources
// included); any change, or a file that does not parse, means the pass runs again. Values are
// stored bit for bit, so outputs do not depend on whether the cache was used.
#pragma once

#include "demlight/geo/dem.h"

#include <cstddef>
#include <optional>
#include <string>

namespace demlight {

/// The pass's results, as GridFrame and DemSource keep them.
struct OpeningPass {
    std::size_t width = 0, height = 0;
    float lowM = 0, highM = 0;
    std::size_t validCells = 0;
    double meanHeightM = 0;
    double steepStepShare = 0;
};

/// Where and for which DEMs the results are kept.
struct OpeningCache {
    /// The folder of the cache files; empty = no cache.
    std::string folder;
    /// DEMs with fewer cells are not cached: their pass takes well under a second.
    std::size_t minCells = std::size_t{16} << 20;

    /// $DEMLIGHT_CACHE_DIR, else $XDG_CACHE_HOME/demlight, else $HOME/.cache/demlight; none when
    /// DEMLIGHT_CACHE_DIR is set and empty, or DEMLIGHT_CACHE=off.
    static OpeningCache fromEnvironment();

    /// The kept results for the DEM at `path` opened with `heights`, when a cache file exists
    /// whose key matches the files as they are now; nullopt otherwise (never throws).
    std::optional<OpeningPass> find(const std::string& path, const HeightOptions& heights) const;
    /// Keeps `pass` for the DEM (created with mode 0600 in a folder of mode 0700, written whole
    /// under a temporary name and renamed); a failure to write is not an error (the next
    /// process runs the pass). Does nothing below minCells or without a folder.
    void keep(const std::string& path, const HeightOptions& heights, const OpeningPass& pass) const;
};

}  // namespace demlight
