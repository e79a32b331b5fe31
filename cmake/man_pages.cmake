# Man pages made by help2man from the binary's own --help (Debian: help2man):
# crowdprof(1) for the top level, which lists the commands, and one page per
# command, crowdprof-bench(1) ..., since only a command's --help lists its
# options. Built with everything else (not by `./setup.sh run`), installed to
# share/man/man1. Without help2man the build has no man pages, and says so.
find_program(CROWDPROF_HELP2MAN help2man DOC "help2man (Debian: help2man), makes the man pages")
if(NOT CROWDPROF_HELP2MAN)
  message(WARNING "help2man not found: no man pages (Debian: apt-get install help2man)")
  return()
endif()

set(man_dir ${CMAKE_BINARY_DIR}/man)
# NAME lines: what each command does, in a few words.
set(crowdprof_man_info "print what a character or a scene file holds")
set(crowdprof_man_gen "write the procedural humanoid as glTF")
set(crowdprof_man_bench "run a crowd and print where each frame's time goes")
set(crowdprof_man_compare "run several modes side by side on one crowd")
set(crowdprof_man_capacity "find the largest crowd each mode fits in a time budget")
set(crowdprof_man_advise "find which levers fit a crowd in a frame budget")
set(crowdprof_man_check "fail when a run got slower than a stored baseline or a base build")
set(crowdprof_man_diff "compare two results metric by metric")
set(crowdprof_man_render "draw one frame of a crowd as a PNG")
set(crowdprof_man_report "write an HTML report of results")
# Every command of `crowdprof --help` (tests/install/install_test.sh checks it).
set(commands info gen bench compare capacity advise check diff render report)

set(see_also "")
foreach(command IN LISTS commands)
  list(APPEND see_also "\\fBcrowdprof-${command}\\fR(1)")
endforeach()
list(JOIN see_also ",\n" see_also)
file(WRITE ${man_dir}/extra-sections.h2m "[FILES]
.TP
\\fIshare/crowdprof/scenes/\\fR under the install prefix (\\fI/usr\\fR for the .deb packages, \\fI/usr/local\\fR for \\fBcmake --install\\fR by default)
The default scenes: \\fIthesis.json\\fR (the thesis's 160 dancing copies, what the examples bench),
\\fImixed.json\\fR (three characters), \\fIlocomotion.json\\fR (a crowd that changes action) and \\fIhumanoid.glb\\fR. The examples' \\fIscenes/\\fR paths are relative to
a source checkout; installed, a relative path not found in the current folder is taken from \\fIshare/crowdprof\\fR,
so the examples run from any folder.
.TP
\\fIshare/doc/crowdprof/\\fR under the install prefix
\\fIREADME.md\\fR and the guides the options name, \\fIdocs/*.md\\fR (\\fIdocs/modes.md\\fR, \\fIdocs/scenes.md\\fR, ...).
[SEE ALSO]
\\fBcrowdprof\\fR(1),
${see_also}
")

set(help2man ${CROWDPROF_HELP2MAN} --no-info --version-string=${PROJECT_VERSION}
  --include=${man_dir}/extra-sections.h2m)
set(pages ${man_dir}/crowdprof.1)
add_custom_command(OUTPUT ${man_dir}/crowdprof.1
  COMMAND ${help2man} --name "profile skinned-crowd scenes" --output=${man_dir}/crowdprof.1
          $<TARGET_FILE:crowdprof_cli>
  DEPENDS crowdprof_cli ${man_dir}/extra-sections.h2m COMMENT "Man page crowdprof(1)" VERBATIM)
foreach(command IN LISTS commands)
  # help2man names a page after its program: a one-line wrapper per command.
  set(wrapper ${man_dir}/bin/crowdprof-${command})
  file(GENERATE OUTPUT ${wrapper} CONTENT "#!/bin/sh\nexec '$<TARGET_FILE:crowdprof_cli>' ${command} \"$@\"\n"
       FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
  add_custom_command(OUTPUT ${man_dir}/crowdprof-${command}.1
    COMMAND ${help2man} --name "${crowdprof_man_${command}}" --output=${man_dir}/crowdprof-${command}.1 ${wrapper}
    DEPENDS crowdprof_cli ${man_dir}/extra-sections.h2m COMMENT "Man page crowdprof-${command}(1)" VERBATIM)
  list(APPEND pages ${man_dir}/crowdprof-${command}.1)
endforeach()
add_custom_target(crowdprof_man_pages ALL DEPENDS ${pages})
install(FILES ${pages} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
