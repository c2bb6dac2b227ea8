"""The `demlight` Processing provider: one algorithm per raster command of the demlight CLI it
finds (cli.find_executable), built from that CLI's `options --json`."""

import os

from qgis.core import Qgis, QgsMessageLog, QgsProcessingProvider

from . import cli
from .algorithm import DemlightAlgorithm, is_algorithm

#: The Processing setting (Settings > Options > Processing > Providers > demlight) naming the CLI.
EXECUTABLE_SETTING = "DEMLIGHT_EXECUTABLE"


def _configured_executable():
    try:
        from processing.core.ProcessingConfig import ProcessingConfig
    except ImportError:
        return None
    return ProcessingConfig.getSetting(EXECUTABLE_SETTING)


class DemlightProvider(QgsProcessingProvider):

    def __init__(self):
        super().__init__()
        self._version = None

    def id(self):
        return "demlight"

    def name(self):
        return "demlight"

    def longName(self):
        return f"demlight {self._version}" if self._version else "demlight"

    def load(self):
        try:
            from processing.core.ProcessingConfig import ProcessingConfig, Setting
            ProcessingConfig.addSetting(Setting(self.name(), EXECUTABLE_SETTING, "demlight executable", "",
                                                valuetype=Setting.FILE))
            ProcessingConfig.readSettings()
        except ImportError:
            pass
        self.refreshAlgorithms()
        return True

    def unload(self):
        try:
            from processing.core.ProcessingConfig import ProcessingConfig
            ProcessingConfig.removeSetting(EXECUTABLE_SETTING)
        except ImportError:
            pass

    def supportedOutputRasterLayerExtensions(self):
        return ["tif"]  # the CLI writes GeoTIFF (GTiff or COG), and requires the name to say so

    def defaultRasterFileExtension(self):
        return "tif"

    def loadAlgorithms(self):
        executable = cli.find_executable(_configured_executable())
        if executable is None:
            QgsMessageLog.logMessage(
                f"demlight: no demlight executable (set ${cli.EXECUTABLE_ENV}, the provider's "
                f"'{EXECUTABLE_SETTING}' setting, or put demlight on PATH); no algorithms", "Processing",
                Qgis.Warning)
            return
        try:
            description = cli.load_commands(executable)
        except cli.DemlightError as e:
            QgsMessageLog.logMessage(f"demlight: {e}", "Processing", Qgis.Critical)
            return
        self._version = description["version"]
        for command in description["commands"]:
            if is_algorithm(command):
                self.addAlgorithm(DemlightAlgorithm(command, os.path.abspath(executable)))
