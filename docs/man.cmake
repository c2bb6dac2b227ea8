# Writes the man page demlight.1 with help2man from the built program's own --help: the root
# help gives NAME, SYNOPSIS and OPTIONS, and a COMMANDS section holds each command's --help, the
# commands taken from the root help's list. Nothing is copied from the sources, so the page
# cannot drift from the program.
# cmake -DDEMLIGHT=path/to/demlight -DHELP2MAN=path/to/help2man -DOUTPUT=demlight.1 -P man.cmake
foreach(var DEMLIGHT HELP2MAN OUTPUT)
  if(NOT ${var})
    message(FATAL_ERROR "man.cmake: -D${var}=... is required")
  endif()
endforeach()

execute_process(COMMAND ${DEMLIGHT} --help OUTPUT_VARIABLE root_help RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "man.cmake: '${DEMLIGHT} --help' failed (${rc})")
endif()

# The command names: the first word of each indented line after "Subcommands:".
string(REGEX REPLACE ".*\nSubcommands:\n" "" command_lines "${root_help}")
string(REPLACE "\n" ";" command_lines "${command_lines}")
set(commands "")
foreach(line IN LISTS command_lines)
  if(line MATCHES "^  ([a-z][a-z0-9-]*) ")
    list(APPEND commands ${CMAKE_MATCH_1})
  elseif(NOT line MATCHES "^ ")
    break()
  endif()
endforeach()
list(LENGTH commands count)
if(count EQUAL 0)
  message(FATAL_ERROR "man.cmake: no commands found in '${DEMLIGHT} --help'")
endif()

set(include_text "[COMMANDS]\nEach command's own \\fB--help\\fR follows.\n")
foreach(command IN LISTS commands)
  execute_process(COMMAND ${DEMLIGHT} ${command} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "man.cmake: '${DEMLIGHT} ${command} --help' failed (${rc})")
  endif()
  # roff: backslashes escaped, lines starting with a control character made literal.
  string(REPLACE "\\" "\\e" help "${help}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" help "${help}")
  string(APPEND include_text ".SS demlight ${command}\n.nf\n${help}.fi\n")
endforeach()
string(APPEND include_text "[SEE ALSO]\nThe full reference with bands, units and metadata keys is docs/commands.md in the source tree.\n")

get_filename_component(out_dir "${OUTPUT}" DIRECTORY)
set(include_file "${out_dir}/demlight.h2m")
file(WRITE "${include_file}" "${include_text}")
execute_process(
  COMMAND ${HELP2MAN} --no-info --section=1 --name "light real terrain from a georeferenced DEM"
          --include=${include_file} --output=${OUTPUT} ${DEMLIGHT}
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "man.cmake: help2man failed (${rc}): ${err}")
endif()
