"""The plugin QGIS loads: it registers the provider in initProcessing, which qgis_process calls
too (initGui is the desktop's only), so the algorithms exist headless as well."""

from qgis.core import QgsApplication

from .provider import DemlightProvider


class DemlightPlugin:

    def __init__(self, iface=None):
        self._iface = iface
        self._provider = None

    def initProcessing(self):
        if self._provider is None:
            self._provider = DemlightProvider()
            QgsApplication.processingRegistry().addProvider(self._provider)

    def initGui(self):
        self.initProcessing()

    def unload(self):
        if self._provider is not None:
            QgsApplication.processingRegistry().removeProvider(self._provider)
            self._provider = None
