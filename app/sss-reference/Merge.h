// sss-reference's merge subcommand, and what it shares with the render.
#pragma once

#include <string>
#include <vector>

namespace sss::app {

// Whether every non-empty file's folder exists; where one does not, says so on stderr
// (an output folder that is not there fails before a long render, not after it).
bool folders_exist(const std::vector<const std::string*>& files);

// sss-reference merge TILE.exr... --out FILE.exr [--variance FILE.exr] [--png FILE.png]:
// the tiles of one --tile K/N render put back together (argv[0] is "merge").
int merge_main(int argc, char** argv);

}  // namespace sss::app
