#pragma once
#include <string>

namespace slender {

// Why `path` cannot be created or written, in the user's words: a missing or read-only
// folder, a path that is a folder, a read-only file. Empty when none of these holds.
std::string why_not_writable(const std::string& path);

// Throws InputError("<what> '<path>' cannot be written: <reason>") when why_not_writable
// finds a reason; lets a deck fail at the line that names the file, not when it is first
// written (a guard's last-good file is written only when the guard fires).
void require_writable(const std::string& what, const std::string& path);

}  // namespace slender
