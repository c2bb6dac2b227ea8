// The camera and atmosphere options of an oblique view, shared by `view` and `timelapse --view`.
#pragma once

#include "demlight/run/parameters.h"

#include "demlight/products/view.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace demlight::cli {

struct ViewCameraOptions {
    double cameraAzimuthDeg = ViewCameraRequest{}.azimuthDeg, cameraElevationDeg = ViewCameraRequest{}.elevationDeg;
    std::optional<double> cameraDistanceM;
    std::string eye, eyeXy, target, targetXy;
    double fovDeg = ViewCameraRequest{}.fieldOfViewDeg;
    std::string size = "1280x720";
    double exaggeration = 1;
    double treeLineM = ViewRequest{}.treeLineM, snowLineM = ViewRequest{}.snowLineM;
    bool noHaze = false, noSky = false;
    double visibilityKm = ViewAtmosphere{}.visibilityKm;
    std::string nodata = "hole";
};

/// --camera-azimuth, --camera-elevation, --camera-distance, --eye, --eye-xy, --target,
/// --target-xy, --fov, --size, --exaggeration, --tree-line, --snow-line, --no-haze, --no-sky,
/// --visibility and --nodata.
void declareViewCameraOptions(ParameterSet& set, ViewCameraOptions& o);

/// The camera, landscape and atmosphere fields of `request` from the options.
void applyViewCameraOptions(const ViewCameraOptions& o, ViewRequest& request);

}  // namespace demlight::cli
