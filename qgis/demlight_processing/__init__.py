"""demlight Processing provider for QGIS: the demlight CLI's raster commands as algorithms."""


def classFactory(iface):
    from .plugin import DemlightPlugin
    return DemlightPlugin(iface)
