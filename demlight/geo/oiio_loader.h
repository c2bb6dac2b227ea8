// Loads libdemlight_oiio.so (demlight/geo/plugin/oiio_plugin.h) on first use, from the folder of the
// running demlight binary.
#pragma once

#include "demlight/geo/plugin/oiio_plugin.h"

namespace demlight {

struct OiioPlugin {
    decltype(&demlight_oiio_check) check;
    decltype(&demlight_oiio_write) write;
    decltype(&demlight_oiio_gif_open) gifOpen;
    decltype(&demlight_oiio_gif_add) gifAdd;
    decltype(&demlight_oiio_gif_close) gifClose;
    decltype(&demlight_oiio_gif_free) gifFree;
    decltype(&demlight_oiio_text_size) textSize;
    decltype(&demlight_oiio_draw_text) drawText;
};

/// The plugin's functions; loads it the first time (thread-safe). Throws Error, naming the
/// file looked for, when it is missing or of another version.
const OiioPlugin& oiioPlugin();

}  // namespace demlight
