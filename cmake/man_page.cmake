# Writes OUT, holoray's man page, with help2man from `holoray --help` and
# `holoray --version` (the release in the footer, the whole text, commit and
# libraries, in a VERSION section), plus a COMMANDS section holding each subcommand's
# `holoray CMD --help` (subcommands as `holoray --help` lists them), put into
# roff here and handed to help2man as an include file. Run by the build
# whenever the binary changes, so the page always matches the options.
# Usage: cmake -DHOLORAY=bin -DHELP2MAN=help2man -DNAME=".." -DOUT=holoray.1 -P man_page.cmake
function(run_holoray out)
  execute_process(COMMAND "${HOLORAY}" ${ARGN} OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "holoray ${ARGN} failed (${rc})")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# One subcommand's --help as roff: a paragraph per group, a tagged paragraph
# per option (help2man's layout), option names in bold.
function(help_to_roff out help)
  string(REPLACE "\\" "\\e" t "\n${help}")
  string(REGEX REPLACE "([ ,=(])(--?[A-Za-z][-A-Za-z0-9]*)" "\\1\\\\fB\\2\\\\fR" t "${t}")
  string(REPLACE "-" "\\-" t "${t}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" t "${t}")
  string(REGEX REPLACE "\n\n+" "\n" t "${t}")
  string(REGEX REPLACE "\nUsage: ([^\n]*)" "\n.PP\nUsage: \\1" t "${t}")
  string(REGEX REPLACE "\n([A-Z][A-Za-z ]*):\n" "\n.PP\n\\\\fI\\1:\\\\fR\n" t "${t}")
  # "  TAG  description" on one line, or "  TAG" with the description below.
  string(REGEX REPLACE "\n  ([^ \n]+( [^ \n]+)*)  +([^ \n])" "\n.TP\n\\1\n\\3" t "${t}")
  string(REGEX REPLACE "\n  ([^ \n][^\n]*)\n   +([^ \n])" "\n.TP\n\\1\n\\2" t "${t}")
  string(REGEX REPLACE "^\n" "" t "${t}")
  set(${out} "${t}" PARENT_SCOPE)
endfunction()

run_holoray(help --help)
string(FIND "${help}" "\nSubcommands:\n" at)
if(at LESS 0)
  message(FATAL_ERROR "holoray --help lists no subcommands")
endif()
string(SUBSTRING "${help}" ${at} -1 listing)
# Only the list itself: the examples that follow it name commands too.
string(REGEX REPLACE "^(\nSubcommands:\n[^\n]*(\n  [^\n]*)*).*" "\\1" listing "${listing}")
string(REGEX MATCHALL "\n  [a-z][-a-z0-9]*" commands "${listing}")
set(include "[COMMANDS]\n")
foreach(c IN LISTS commands)
  string(STRIP "${c}" c)
  run_holoray(sub ${c} --help)
  help_to_roff(roff "${sub}")
  string(APPEND include ".SS \"holoray ${c}\"\n${roff}")
endforeach()
# help2man would put what follows --version's first line among the options.
run_holoray(version --version)
string(STRIP "${version}" version)
string(REGEX MATCH "^holoray [^ \n]*" first "${version}")  # the footer: no commit
string(REPLACE "\n" "\n.br\n" version "${version}")
string(APPEND include "[VERSION]\n${version}")
file(WRITE "${OUT}.h2m" "${include}")
execute_process(COMMAND "${HELP2MAN}" --no-info "--name=${NAME}" "--version-string=${first}" "--include=${OUT}.h2m"
                        "--output=${OUT}" "${HOLORAY}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man failed (${rc})")
endif()
