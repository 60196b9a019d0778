// Replacing a file so that nothing is lost (see replace_file.h).
#include "common/app/replace_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "common/base/error.h"
#include "common/render/interrupt.h"

namespace pt {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kNameMax = 255;       // bytes in one file name (ext4, xfs, tmpfs, btrfs)
constexpr std::size_t kKeptNameBytes = 200;  // of a long name, in its temporary name
constexpr const char* kTemporarySuffix = ".pt-tmp";

std::string hex64(std::uint64_t h) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", (unsigned long long)h);
  return text;
}

std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

fs::path folder_of(const fs::path& p) { return p.parent_path().empty() ? fs::path(".") : p.parent_path(); }

// What a file that is not a regular one is, in words; "" for a regular file or none.
const char* not_a_file(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  return "";
}

// The start of every temporary name of `name` (before the PID).
std::string temporary_prefix(const std::string& name) {
  if (1 + name.size() + 1 + 10 + std::strlen(kTemporarySuffix) <= kNameMax) return "." + name + ".";
  return "." + name.substr(0, kKeptNameBytes) + "~" + hex64(fnv1a(name)) + ".";
}

// Whether process `pid` is gone (so its temporary file is stale).
bool process_is_gone(long pid) { return pid > 0 && pid != long(::getpid()) && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH; }

// The PID in `text` from `at` up to `end` (all digits), or -1.
long digits_at(const std::string& text, std::size_t at, std::size_t end) {
  if (end <= at || end - at > 10) return -1;
  for (std::size_t i = at; i < end; i++) {
    if (text[i] < '0' || text[i] > '9') return -1;
  }
  return std::stol(text.substr(at, end - at));
}

// The PID of a temporary file of `name` left by this version or an earlier one, else -1.
long temporary_owner(const std::string& file, const std::string& name) {
  const std::string prefix = temporary_prefix(name), suffix = kTemporarySuffix;
  if (file.size() > prefix.size() + suffix.size() && file.compare(0, prefix.size(), prefix) == 0 &&
      file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0) {
    return digits_at(file, prefix.size(), file.size() - suffix.size());
  }
  // Earlier versions: ".NAME.tmpPID.EXT" (images) and ".NAME.tmpPID" (checkpoints).
  const std::string old = "." + name + ".tmp";
  if (file.size() <= old.size() || file.compare(0, old.size(), old) != 0) return -1;
  std::size_t end = file.find('.', old.size());
  return digits_at(file, old.size(), end == std::string::npos ? file.size() : end);
}

[[noreturn]] void fail(const std::string& what, const std::string& path, const std::string& why, bool had_old,
                       const std::string& todo) {
  throw Error(kExitOutput, "cannot write " + (what.empty() ? "" : what + " ") + "'" + path + "': " + why +
                               (had_old ? " (the old file is unchanged)" : "") + "; " + todo);
}

// The regular file a write to `path` goes to, or "" with `why` saying what else it is.
std::string regular_target(const std::string& path, std::string& why) {
  fs::path p(path);
  for (int hops = 0;; hops++) {
    struct stat st;
    if (::lstat(p.c_str(), &st) != 0) return p.string();  // a new file (the folder is checked elsewhere)
    if (!S_ISLNK(st.st_mode)) {
      const char* what = not_a_file(st.st_mode);
      if (*what) why = std::string("it is ") + what + ", not a file";
      return *what ? "" : p.string();
    }
    std::error_code ec;
    fs::path to = fs::read_symlink(p, ec);
    if (hops == 40 || ec) {
      why = hops == 40 ? "it is a loop of symbolic links" : "its symbolic link cannot be read (" + ec.message() + ")";
      return "";
    }
    p = to.is_absolute() ? to : folder_of(p) / to;
  }
}

bool write_all(int fd, const ByteSpan& span) {
  const char* p = static_cast<const char*>(span.data);
  std::size_t left = span.size;
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;  // a write that takes nothing: the file system is full
      return false;
    }
    p += n, left -= std::size_t(n);
  }
  return true;
}

}  // namespace

std::string output_target(const std::string& path, const std::string& option) {
  std::string why;
  std::string target = regular_target(path, why);
  if (target.empty()) throw Error(kExitOutput, option + " '" + path + "': " + why + "; give the name of a file to write");
  return target;
}

namespace {

// `p` made absolute, with "." and ".." taken out where the path does not lead through an
// existing folder ("new/../x" names x before new/ is made).
fs::path lexical(const std::string& p) {
  std::error_code ec;
  return fs::absolute(p, ec).lexically_normal();
}

bool stat_either(const std::string& p, struct stat& st) {
  return ::stat(p.c_str(), &st) == 0 || ::stat(lexical(p).c_str(), &st) == 0;
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  if (stat_either(a, sa) && stat_either(b, sb)) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(lexical(a), ea), cb = fs::weakly_canonical(lexical(b), eb);
  return !ea && !eb && ca == cb;
}

std::string temporary_path(const std::string& path, long pid) {
  const fs::path p(path);
  return (folder_of(p) / (temporary_prefix(p.filename().string()) + std::to_string(pid) + kTemporarySuffix)).string();
}

int remove_stale_temporaries(const std::string& path) {
  const fs::path p(path);
  const std::string name = p.filename().string();
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(folder_of(p), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string file = it->path().filename().string();
    if (file.empty() || file[0] != '.') continue;
    const long pid = temporary_owner(file, name);
    std::error_code ignored;
    if (pid > 0 && it->is_regular_file(ignored) && process_is_gone(pid) && fs::remove(it->path(), ignored)) removed++;
  }
  return removed;
}

void replace_file(const std::string& path, const std::vector<ByteSpan>& bytes, const std::string& todo,
                  const std::string& what) {
  std::string why;
  const std::string target = regular_target(path, why);
  if (target.empty()) fail(what, path, why, false, "give the name of a file to write");
  remove_stale_temporaries(target);
  const std::string tmp = temporary_path(target, long(::getpid()));
  struct stat old;
  const bool had_old = ::stat(target.c_str(), &old) == 0 && S_ISREG(old.st_mode);

  set_file_in_progress(tmp.c_str());  // a second Ctrl-C removes it
  ::unlink(tmp.c_str());              // one this process left (a PID reused after a crash)
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int e = errno;
    set_file_in_progress("");
    fail(what, path, e == ENAMETOOLONG ? "its name is too long for the file system" : std::string(std::strerror(e)), had_old,
         todo);
  }
  auto give_up = [&](const char* step) {
    std::string why = std::strerror(errno);
    if (*step) why += std::string(" (") + step + ")";
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    set_file_in_progress("");
    fail(what, path, why, had_old, todo);
  };
  if (had_old && ::fchmod(fd, old.st_mode & 07777) != 0) give_up("setting its permissions");
  for (const ByteSpan& span : bytes) {
    if (!write_all(fd, span)) give_up("");
  }
  // On the disk before the rename: the target is the old file or the whole new one.
  if (::fsync(fd) != 0 && errno != EINVAL) give_up("flushing it to the disk");
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) give_up("closing it");
  if (::rename(tmp.c_str(), target.c_str()) != 0) give_up("renaming the finished file over it");
  set_file_in_progress("");
  // The rename itself on the disk (best effort: some file systems refuse to sync a folder).
  int dir = ::open(folder_of(fs::path(target)).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) ::fsync(dir), ::close(dir);
}

}  // namespace pt
