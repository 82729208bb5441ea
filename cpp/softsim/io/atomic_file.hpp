#pragma once
// Files are written to a temporary sibling and renamed into place, so a reader never sees a
// half-written artifact and a failed run leaves nothing behind.
#include <functional>
#include <ostream>
#include <string>

namespace softsim::io {

void write_file_atomic(const std::string& path, const std::string& content);
// Streams through a writer callback (for large files such as VTU) with the same guarantee.
void write_file_atomic(const std::string& path, const std::function<void(std::ostream&)>& writer);

// Reads a whole text file; InputError when it cannot be opened.
std::string read_text_file(const std::string& path);

}  // namespace softsim::io
