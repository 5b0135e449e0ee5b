#pragma once
// Whole-file writes that a reader, or a process killed mid-write, never sees half done: the
// bytes go to <path>.tmp, which is then renamed over <path> (the old file stays whole until
// then). A <path>.tmp left by a killed writer is overwritten by the next write.
#include <string>

namespace slide::io {

// Throws IoError naming the file when it cannot be written or renamed (the old file stays).
void writeFileAtomically(const std::string& path, const std::string& contents);

}  // namespace slide::io
