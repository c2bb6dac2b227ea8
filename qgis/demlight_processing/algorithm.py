"""One Processing algorithm per demlight command, built from the command's declaration
(`demlight options --json`): each parameter QGIS shows becomes a Processing parameter with the
declaration's short label, its help as the tooltip, its choices as a drop-down and its range as
the number's limits; the algorithm's help is written from the same declaration. Running it runs
the CLI, so its outputs are the CLI's; the CLI's error messages name the parameters by their
labels here (DEMLIGHT_PARAMETER_NAMES=qgis)."""

import shlex

from qgis.core import (QgsProcessingAlgorithm, QgsProcessingException, QgsProcessingOutputRasterLayer,
                       QgsProcessingParameterBoolean, QgsProcessingParameterDefinition, QgsProcessingParameterEnum,
                       QgsProcessingParameterFileDestination, QgsProcessingParameterFolderDestination,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterDestination,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterString)

from . import cli, styles

#: The CLI's positional argument (the DEM, or sequence's FIT raster) and -o.
INPUT = "INPUT"
OUTPUT = "OUTPUT"
_OUTPUT_OPTION = "output"

# Picture outputs (render): the formats the CLI picks from the extension (cli/cmd_render.cpp help).
_PICTURE_FILTER = "PNG (*.png);;JPEG (*.jpg *.jpeg);;OpenEXR (*.exr)"

# The CLI's metadata prefix; a companion raster's output is named by the rest of its key
# (DEMLIGHT_TRUNCATION_MASK -> TRUNCATION_MASK).
_METADATA_PREFIX = "DEMLIGHT_"


def parameter_name(option):
    """The Processing parameter of an option: the DEM is INPUT, the output OUTPUT, the rest the
    command line's long name in capitals (--sky-directions -> SKY_DIRECTIONS, --of -> OF)."""
    if option["positional"]:
        return INPUT
    if option["name"] == _OUTPUT_OPTION:
        return OUTPUT
    long = next(f for f in option["flags"] if f.startswith("--"))
    return long[2:].upper().replace("-", "_")


def shown(option):
    """Whether QGIS shows the option (the declaration's front ends)."""
    return "qgis" in option["front_ends"]


def companion_output_name(key):
    return key[len(_METADATA_PREFIX):] if key.startswith(_METADATA_PREFIX) else key


# Commands that write files but make no layer: bench measures the horizon methods (a CSV and a
# chart), a tool for choosing options, not a raster product.
_NOT_ALGORITHMS = {"bench"}


def is_algorithm(command):
    """Commands that read a raster and write rasters, pictures or folders at -o become algorithms
    (not info, sunpos, which print, nor bench)."""
    return (command["output"] is not None and command["name"] not in _NOT_ALGORITHMS
            and any(o["positional"] for o in command["options"]))


def _is_number(option):
    return option["max_values"] == 1 and option["type"] in ("FLOAT", "INT") and not option["choices"]


def _is_integer(option):
    return option["type"] == "INT"


def _spelling(option):
    """The option as the CLI's help names it first: --sky-directions, not its older --directions."""
    return next(f for f in option["flags"] if f.startswith("--"))


def _typed_default(option):
    default = option["default"]
    if default is None or not _is_number(option):
        return default
    return int(float(default)) if _is_integer(option) else float(default)


def help_text(command):
    """The algorithm's help, written for QGIS from the declaration: what it does, then a line per
    parameter with its label and help (no command-line syntax). Plain lines: the dialog shows each
    as a paragraph, qgis_process help prints them as they are."""
    lines = [command["description"] + "."]
    for option in command["options"]:
        if not shown(option):
            continue
        label = option["label"]
        if option["choices"]:
            label += " (" + ", ".join(option["choices"]) + ")"
        lines.append(f"{label}: {option['qgis_help']}")
    return "\n".join(lines)


class DemlightAlgorithm(QgsProcessingAlgorithm):
    """The demlight command `command` (one entry of `options --json`), run by `executable`."""

    def __init__(self, command, executable):
        super().__init__()
        self._command = command
        self._executable = executable

    def createInstance(self):
        return DemlightAlgorithm(self._command, self._executable)

    def name(self):
        return self._command["name"]

    def displayName(self):
        return f"{self._command['name']}: {self._command['description']}"

    def shortDescription(self):
        return self._command["description"]

    def shortHelpString(self):
        return help_text(self._command)

    def initAlgorithm(self, config=None):
        for option in self._command["options"]:
            if not shown(option):
                continue
            parameter = self._parameter(option)
            parameter.setHelp(option["qgis_help"])  # the tooltip
            if option["advanced"]:
                parameter.setFlags(parameter.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
            self.addParameter(parameter)
        for key in self._command["companions"]:
            self.addOutput(QgsProcessingOutputRasterLayer(companion_output_name(key),
                                                          f"Raster named by {key} in {OUTPUT}'s metadata"))

    def _parameter(self, option):
        name, label, optional = parameter_name(option), option["label"], not option["required"]
        if option["positional"]:
            return QgsProcessingParameterRasterLayer(name, label)
        if option["name"] == _OUTPUT_OPTION:
            kind = self._command["output"]
            if kind == "raster":
                return QgsProcessingParameterRasterDestination(name, label)
            if kind == "folder":
                return QgsProcessingParameterFolderDestination(name, label)
            return QgsProcessingParameterFileDestination(name, label, _PICTURE_FILTER if kind == "picture" else "")
        if option["flag"]:
            return QgsProcessingParameterBoolean(name, label, False, True)
        if option["choices"] and option["max_values"] == 1:
            # Static strings: qgis_process takes QUALITY=full, not the choice's index.
            return QgsProcessingParameterEnum(name, label, option["choices"], False, option["default"], optional,
                                              usesStaticStrings=True)
        if _is_number(option):
            kind = QgsProcessingParameterNumber.Integer if _is_integer(option) else QgsProcessingParameterNumber.Double
            parameter = QgsProcessingParameterNumber(name, label, kind, _typed_default(option), optional)
            if option["range"]:  # an open lower end (> 0): its bound itself is left to the CLI's check
                parameter.setMinimum(option["range"]["min"])
                if option["range"]["max"] is not None:
                    parameter.setMaximum(option["range"]["max"])
            return parameter
        return QgsProcessingParameterString(name, label, option["default"], False, optional)

    def _arguments(self, parameters, context):
        """The CLI command line for `parameters`, the outputs it writes and the input raster's
        source; options left at the CLI's default are not passed, so the command is the one a
        user would type."""
        args = [self._executable, self._command["name"]]
        outputs, source = {}, None
        for option in self._command["options"]:
            if not shown(option):
                continue
            name = parameter_name(option)
            if option["positional"]:
                layer = self.parameterAsRasterLayer(parameters, name, context)
                if layer is None:
                    raise QgsProcessingException(f"{INPUT}: cannot open {parameters.get(name)!r} as a raster")
                args.append(layer.source())
                source = layer.source()
                continue
            flag = _spelling(option)
            if option["name"] == _OUTPUT_OPTION:
                if self._command["output"] == "raster":
                    path = self.parameterAsOutputLayer(parameters, name, context)
                elif self._command["output"] == "folder":
                    path = self.parameterAsString(parameters, name, context)
                else:
                    path = self.parameterAsFileOutput(parameters, name, context)
                outputs[OUTPUT] = path
                args += [flag, path]
                continue
            if parameters.get(name) is None:
                continue
            if option["flag"]:
                if self.parameterAsBoolean(parameters, name, context):
                    args.append(flag)
                continue
            if _is_number(option):
                value = (self.parameterAsInt if _is_integer(option) else self.parameterAsDouble)(parameters, name,
                                                                                               context)
                if value == _typed_default(option):
                    continue
                args += [flag, repr(value)]
                continue
            if option["choices"] and option["max_values"] == 1:
                value = self.parameterAsEnumString(parameters, name, context)
            else:
                value = self.parameterAsString(parameters, name, context).strip()
            if not value or value == option["default"]:
                continue
            if option["max_values"] == 1:
                args += [flag, value]
            else:
                args += [flag] + value.split()  # several values, separated by spaces
        return args, outputs, source

    def processAlgorithm(self, parameters, context, feedback):
        args, outputs, source = self._arguments(parameters, context)
        feedback.pushCommandInfo(shlex.join(args))  # quoted: the log's line pastes into a shell
        stage = [None]

        def on_progress(name, percent):
            if name != stage[0]:
                stage[0] = name
                feedback.setProgressText(name)
            feedback.setProgress(percent)

        def on_line(line):
            if not line.startswith(cli.ERROR_PREFIX):  # errors go into the exception, once
                feedback.pushConsoleInfo(line)

        code, messages = cli.run(args, on_progress, on_line, feedback.isCanceled, parameter_names="qgis")
        if feedback.isCanceled():
            raise QgsProcessingException("demlight: cancelled")
        if code != 0:
            errors = [m for m in messages if m.startswith(cli.ERROR_PREFIX)] or messages
            raise QgsProcessingException("\n".join(errors) or f"demlight exited with code {code}")
        self._name_and_style(outputs[OUTPUT], source, context)
        outputs.update(self._companions(outputs[OUTPUT]))
        return outputs

    def _name_and_style(self, path, source, context):
        """The raster QGIS loads when the algorithm ends is named after the command and its input
        ("sun – fuji_dem", not "Output raster path") and drawn with the command's style."""
        if self._command["output"] != "raster" or not context.willLoadLayerOnCompletion(path):
            return
        details = context.layerToLoadOnCompletionDetails(path)
        details.name = styles.layer_name(self.name(), source)
        details.forceName = True
        if self.name() in styles.BAND_STYLES:
            details.setPostProcessor(styles.StylePostProcessor.create(self.name()))

    def _companions(self, path):
        """The rasters written with the -o raster, from the metadata items that name them."""
        if not self._command["companions"]:
            return {}
        from osgeo import gdal
        dataset = gdal.Open(path)
        if dataset is None:
            raise QgsProcessingException(f"{OUTPUT}: cannot open {path}")
        return {companion_output_name(key): dataset.GetMetadataItem(key) for key in self._command["companions"]}
