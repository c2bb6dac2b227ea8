#include "demlight/geo/gdal_session.h"

#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace demlight::detail {
namespace {

thread_local std::string lastGdalError;

void CPL_STDCALL collectError(CPLErr level, CPLErrorNum, const char* message) {
    if (level >= CE_Failure && message) lastGdalError = message;
}

}  // namespace

void ensureGdal() {
    static std::once_flag once;
    std::call_once(once, [] {
        GDALAllRegister();
        CPLSetErrorHandler(collectError);
    });
}

std::string takeGdalError() {
    std::string message;
    message.swap(lastGdalError);
    return message;
}

}  // namespace demlight::detail
