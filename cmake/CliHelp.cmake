# Reads mocaplink's command line from the binary itself (issue 29): each subcommand's `--help`, as
# CLI11 prints it from the options that apps/mocaplink/cmd_*.cpp declare. That declaration is the
# one source of the command line's reference: packaging/manpage.cmake turns this text into the man
# page and tests/packaging/readme_cli.cmake holds README.md's "Subcommands" list against it.
# Script mode (cmake -P) only. MOCAPLINK_RUN: the command that runs the binary, as a list (under
# the cross presets CMAKE_CROSSCOMPILING_EMULATOR first), or joined with "|".

string(REPLACE "|" ";" MOCAPLINK_RUN "${MOCAPLINK_RUN}")

# CMake lists split at ";" outside square brackets, and help text has both ("{"vectors":[...]}").
# The text these functions return has them as the control characters 1, 2, 3, so that its lines
# can be list items; mocaplink_cli_plain turns such text back.
string(ASCII 1 cli_lbracket)
string(ASCII 2 cli_rbracket)
string(ASCII 3 cli_semicolon)
macro(mocaplink_cli_plain var)
  string(REPLACE "${cli_lbracket}" "[" ${var} "${${var}}")
  string(REPLACE "${cli_rbracket}" "]" ${var} "${${var}}")
  string(REPLACE "${cli_semicolon}" ";" ${var} "${${var}}")
endmacro()

# mocaplink_cli_help(OUT [SUBCOMMAND...]): the --help text of `mocaplink SUBCOMMAND...`, with the
# program's path in "Usage:" shown as `mocaplink`, brackets and semicolons encoded (above). Fails on
# a non-zero exit.
function(mocaplink_cli_help out)
  execute_process(COMMAND ${MOCAPLINK_RUN} ${ARGN} --help RESULT_VARIABLE status
                  OUTPUT_VARIABLE text ERROR_VARIABLE error)
  if(NOT status EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "mocaplink ${command} --help failed (${status}): ${error}")
  endif()
  string(REGEX REPLACE "\nUsage: [^ \n]+" "\nUsage: mocaplink" text "${text}")
  string(REPLACE "[" "${cli_lbracket}" text "${text}")
  string(REPLACE "]" "${cli_rbracket}" text "${text}")
  string(REPLACE ";" "${cli_semicolon}" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# mocaplink_cli_section(OUT TEXT NAME): the entries of a --help section ("Options", "Positionals",
# "Subcommands"), one list item an entry, each "NAME|DESCRIPTION" (NAME as CLI11 prints it, e.g.
# "--seconds FLOAT:POSITIVE"; DESCRIPTION may be empty).
function(mocaplink_cli_section out text name)
  set(entries "")
  set(inside FALSE)
  string(REPLACE "\n" ";" lines "${text}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^${name}:$")
      set(inside TRUE)
    elseif(line MATCHES "^[^ ]")
      set(inside FALSE)
    elseif(inside AND line MATCHES "^  ([^ ].*[^ ])  +([^ ].*)$")
      list(APPEND entries "${CMAKE_MATCH_1}|${CMAKE_MATCH_2}")
    elseif(inside AND line MATCHES "^  ([^ ].*[^ ]) *$")
      list(APPEND entries "${CMAKE_MATCH_1}|")
    endif()
  endforeach()
  set(${out} "${entries}" PARENT_SCOPE)
endfunction()

# mocaplink_cli_commands(OUT): every subcommand that runs something, depth first in --help's order,
# each as its words joined by spaces ("run", ..., "mavlink encode"); groups (`mavlink`) left out.
function(mocaplink_cli_commands out)
  set(result "")
  set(queue "")
  mocaplink_cli_help(text)
  mocaplink_cli_section(entries "${text}" Subcommands)
  foreach(entry IN LISTS entries)
    string(REGEX REPLACE "\\|.*" "" name "${entry}")
    list(APPEND queue "${name}")
  endforeach()
  while(queue)
    list(POP_FRONT queue command)
    string(REPLACE " " ";" words "${command}")
    mocaplink_cli_help(text ${words})
    mocaplink_cli_section(children "${text}" Subcommands)
    if(NOT children)
      list(APPEND result "${command}")
    endif()
    set(prefix "")
    foreach(entry IN LISTS children)
      string(REGEX REPLACE "\\|.*" "" name "${entry}")
      list(APPEND prefix "${command} ${name}")
    endforeach()
    list(PREPEND queue ${prefix})
  endwhile()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()
