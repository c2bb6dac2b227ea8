"""How an algorithm's raster output looks when QGIS loads it: the layer is named after the
command and its input ("sun – fuji_dem") and drawn as one band in a colour ramp with a legend,
from the QML style shipped for the command in styles/ (made by qgis/make_styles.py). Commands
whose band's range depends on the period (insolation, sunhours) get the range of the values
written."""

import os

from qgis.core import QgsProcessingLayerPostProcessorInterface, QgsRasterBandStats

STYLES_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "styles")

#: Per command: the band users want first (1-based), its range (None: the band's own minimum and
#: maximum), the ramp, and the legend's title. The QML files hold the fixed ranges.
BAND_STYLES = {
    "sun": (1, (0.0, 1.0), "Magma", "sun_visibility (share of the sun's disk)"),
    "sky": (1, (0.0, 1.0), "Viridis", "svf_horizontal (sky-view factor)"),
    "horizon": (1, (0.0, 30.0), "Viridis", "horizon elevation, first azimuth (deg)"),
    "aperture": (4, (0.0, 90.0), "Viridis", "aperture_radius_deg (deg)"),
    "light": (1, (0.0, 1.0), "Magma", "light (normalised irradiance)"),
    "irradiance": (4, (0.0, 1000.0), "Inferno", "global irradiance (W/m²)"),
    "insolation": (4, None, "Inferno", "global irradiation (kWh/m²)"),
    "sunhours": (1, None, "Inferno", "sun_hours (h)"),
}


def style_path(command):
    return os.path.join(STYLES_DIR, command + ".qml")


def layer_name(command, input_path):
    """"sun – fuji_dem": the command and the input's file name without its extension."""
    stem = os.path.splitext(os.path.basename(str(input_path)))[0] if input_path else ""
    return f"{command} – {stem}" if stem else command


class StylePostProcessor(QgsProcessingLayerPostProcessorInterface):
    """Applies the command's QML to the loaded layer (and the values' range where it depends on
    them). QGIS keeps only a pointer to a post-processor: `create` keeps the Python object alive
    in a module-level list for as long as QGIS may call it."""

    _alive = []

    def __init__(self, command):
        super().__init__()
        self._command = command

    @classmethod
    def create(cls, command):
        processor = cls(command)
        cls._alive.append(processor)
        return processor

    def postProcessLayer(self, layer, context, feedback):
        apply_style(layer, self._command)


def apply_style(layer, command):
    """Styles `layer` (a raster layer of `command`'s output) as BAND_STYLES says; False when the
    command has no style or the layer is not what the style expects (a colour `light` has three
    bands and keeps QGIS's RGB drawing)."""
    if command not in BAND_STYLES or not os.path.exists(style_path(command)):
        return False
    band, value_range, _, _ = BAND_STYLES[command]
    if layer.bandCount() < band or (command == "light" and layer.bandCount() != 1):
        return False
    _, ok = layer.loadNamedStyle(style_path(command))
    if not ok:
        return False
    if value_range is None:
        stats = layer.dataProvider().bandStatistics(band, QgsRasterBandStats.Min | QgsRasterBandStats.Max)
        renderer = layer.renderer()
        shader = renderer.shader().rasterShaderFunction()
        lo, hi = stats.minimumValue, max(stats.maximumValue, stats.minimumValue + 1e-6)
        renderer.setClassificationMin(lo)
        renderer.setClassificationMax(hi)
        shader.setMinimumValue(lo)
        shader.setMaximumValue(hi)
        shader.classifyColorRamp(5, band, layer.extent(), layer.dataProvider())
    layer.triggerRepaint()
    return True
