// Replacing a file so that nothing is lost: every file the programs write (images, error
// maps, z-maps, merged films, checkpoints) goes through here. The bytes are made in memory
// first; then a temporary file beside the target takes them with every write and the close
// checked, is flushed to the disk (fsync) and only then renamed over the target. A full disk,
// a killed process or a failed write leaves the old file whole and says so in one line.
// Not part of the article: the machinery around its algorithms (docs/reliability.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pt {

// One piece of the file's bytes (a file may be written from several buffers without
// copying them into one).
struct ByteSpan {
  const void* data;
  std::size_t size;
};

// Where a write to `path` really goes: the path itself, or for a symbolic link the regular
// file at its end (the link stays a link). Throws pt::Error(kExitOutput) with one line when
// the path is a folder, a device, a FIFO or a socket, or the link is a loop. `option` names
// the command-line option in messages ("--out").
std::string output_target(const std::string& path, const std::string& option);

// Whether two paths name the same file: the same device and inode where both exist, else
// the same target path once links and "." / ".." are resolved.
bool same_file(const std::string& a, const std::string& b);

// Replaces the file `path` (through a link, at its end) by the bytes, atomically: on any
// failure it throws pt::Error(kExitOutput) whose message starts with "cannot write WHAT
// 'PATH': " and names the reason (e.g. "No space left on device"), and `path` is the old
// file. The new file keeps the old file's permission bits. `todo` ends the message (what the
// user can do); `what` names the kind of file ("checkpoint"), or nothing.
void replace_file(const std::string& path, const std::vector<ByteSpan>& bytes, const std::string& todo,
                  const std::string& what = "");

// The temporary name replace_file() writes `path` to: ".NAME.PID.pt-tmp" beside it, with
// NAME shortened (and a hash of the whole name added) where the whole would pass the
// file system's 255-byte limit.
std::string temporary_path(const std::string& path, long pid);

// Removes the temporary files that earlier runs writing `path` left behind when they were
// killed (SIGKILL, power loss): those whose process no longer runs. Also the names of
// earlier versions (".NAME.tmpPID.ext", ".NAME.tmpPID"). Returns how many were removed.
int remove_stale_temporaries(const std::string& path);

}  // namespace pt
