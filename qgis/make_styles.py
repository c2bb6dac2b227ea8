#!/usr/bin/env python3
"""Writes the provider's QML styles (qgis/demlight_processing/styles/COMMAND.qml) from
BAND_STYLES in styles.py: one band in a pseudocolour ramp of QGIS's default style, five classes
over the band's range. Run after changing BAND_STYLES: QT_QPA_PLATFORM=offscreen
python3 qgis/make_styles.py (needs python3-qgis and GDAL's Python bindings)."""

import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from osgeo import gdal, osr  # noqa: E402
from qgis.core import (QgsApplication, QgsColorRampShader, QgsRasterLayer, QgsRasterShader,  # noqa: E402
                       QgsSingleBandPseudoColorRenderer, QgsStyle)


def main():
    app = QgsApplication([], False)
    app.initQgis()
    from demlight_processing.styles import BAND_STYLES, STYLES_DIR
    os.makedirs(STYLES_DIR, exist_ok=True)
    gdal.PushErrorHandler("CPLQuietErrorHandler")  # statistics of the empty scratch bands
    with tempfile.TemporaryDirectory() as scratch:
        for command, (band, value_range, ramp_name, title) in sorted(BAND_STYLES.items()):
            path = os.path.join(scratch, command + ".tif")
            ds = gdal.GetDriverByName("GTiff").Create(path, 4, 4, band, gdal.GDT_Float32)
            srs = osr.SpatialReference()
            srs.ImportFromEPSG(32610)
            ds.SetProjection(srs.ExportToWkt())
            ds.SetGeoTransform([0, 1, 0, 0, 0, -1])
            ds = None
            layer = QgsRasterLayer(path, command)
            lo, hi = value_range or (0.0, 1.0)
            ramp = QgsStyle.defaultStyle().colorRamp(ramp_name)
            if ramp is None:
                raise SystemExit(f"QGIS's default style has no colour ramp {ramp_name!r}")
            colour_shader = QgsColorRampShader(lo, hi, ramp, QgsColorRampShader.Interpolated)
            colour_shader.classifyColorRamp(5, band, layer.extent(), layer.dataProvider())
            shader = QgsRasterShader(lo, hi)
            shader.setRasterShaderFunction(colour_shader)
            renderer = QgsSingleBandPseudoColorRenderer(layer.dataProvider(), band, shader)
            renderer.setClassificationMin(lo)
            renderer.setClassificationMax(hi)
            layer.setRenderer(renderer)
            out = os.path.join(STYLES_DIR, command + ".qml")
            message, ok = layer.saveNamedStyle(out)
            if not ok:
                raise SystemExit(f"{out}: {message}")
            print("wrote", out, "-", title)
    app.exitQgis()


if __name__ == "__main__":
    main()
