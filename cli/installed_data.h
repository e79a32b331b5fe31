// Where an installed crowdprof keeps what it ships: <prefix>/share/crowdprof
// (the scenes) beside <prefix>/bin/crowdprof, and <prefix>/share/doc/crowdprof
// (README.md and docs/). The examples of --help and of the man pages name
// scenes as a source checkout holds them (scenes/thesis.json); installed, the
// same relative paths are found under share/crowdprof, so those examples run
// from any folder.
#pragma once

#include <string>

// `path` when it exists here (or is absolute, or names nothing under the
// installed data folder); else the installed file it names, with a note on
// stderr saying so. FILE#skin=N keeps its suffix.
std::string with_installed_data(const std::string& path);

// This binary's installed data folder (<prefix>/share/crowdprof), or "" when
// it runs from elsewhere (a build tree).
std::string installed_data_dir();
