#pragma once
// Input files are checked before a library opens them: a directory, a FIFO
// (which would block forever) or a device such as /dev/zero (which never
// ends) is named as what it is, not reported as "no such file" or left to
// hang the render.
#include <string>

namespace weft {

// Throws weft::Error "<what> '<path>': ..." unless path is a regular file
// (symbolic links are followed).
void requireRegularFile(const std::string& path, const std::string& what);

}  // namespace weft
