# Writes mocaplink's man page (issue 29): packaging/mocaplink.1.in with its COMMANDS section made
# from each subcommand's --help (cmake/CliHelp.cmake), gzipped as Debian wants it (gzip -9n: no
# name or time stamp in the header). Run at build time by cmake/Packaging.cmake:
#   cmake -DMOCAPLINK_RUN=BINARY -DTEMPLATE=mocaplink.1.in -DVERSION=X.Y.Z -DOUTPUT=mocaplink.1.gz
#         -P packaging/manpage.cmake
cmake_policy(VERSION 3.25)
include(${CMAKE_CURRENT_LIST_DIR}/../cmake/CliHelp.cmake)

# Text as roff reads it: backslashes escaped, a line-initial "." or "'" made literal, "-" a
# hyphen-minus (options are typed).
function(roff_escape out text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "^([.'])" "\\\\&\\1" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

mocaplink_cli_commands(commands)
set(roff "")
foreach(command IN LISTS commands)
  string(REPLACE " " ";" words "${command}")
  mocaplink_cli_help(text ${words})
  # The first line says what it does, the second is "Usage: ...".
  string(REGEX MATCH "^([^\n]*)\nUsage: ([^\n]*)" _ "${text}")
  set(summary "${CMAKE_MATCH_1}")
  set(usage "${CMAKE_MATCH_2}")
  roff_escape(usage "${usage}")
  roff_escape(summary "${summary}")
  string(APPEND roff ".SS \"mocaplink ${command}\"\n.B ${usage}\n.PP\n${summary}\n")
  foreach(section Positionals Options)
    mocaplink_cli_section(entries "${text}" ${section})
    foreach(entry IN LISTS entries)
      string(REGEX MATCH "^([^|]*)\\|(.*)$" _ "${entry}")
      set(name "${CMAKE_MATCH_1}")
      set(description "${CMAKE_MATCH_2}")
      if(name STREQUAL "-h,--help")
        continue()  # every subcommand has it; SYNOPSIS says so once
      endif()
      roff_escape(name "${name}")
      roff_escape(description "${description}")
      string(APPEND roff ".TP\n.B ${name}\n${description}\n")
    endforeach()
  endforeach()
endforeach()
mocaplink_cli_plain(roff)
string(REGEX REPLACE "\n$" "" roff "${roff}")

file(READ ${TEMPLATE} page)
string(REPLACE "@VERSION@" "${VERSION}" page "${page}")
string(REPLACE "@COMMANDS@" "${roff}" page "${page}")
get_filename_component(plain ${OUTPUT} NAME_WLE)
get_filename_component(dir ${OUTPUT} DIRECTORY)
file(WRITE ${dir}/${plain} "${page}")
find_program(GZIP gzip REQUIRED)
execute_process(COMMAND ${GZIP} -9nf ${dir}/${plain} COMMAND_ERROR_IS_FATAL ANY)
