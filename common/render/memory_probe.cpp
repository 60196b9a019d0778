// The memory probe (memory.h): what this process may still take, from /proc/meminfo, its
// cgroup (v1 or v2) and RLIMIT_AS, each file parsed strictly and left out when it cannot be.
// Not part of the article: the machinery of the stage programs.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/render/memory.h"

namespace pt {

std::string memory_size_words(std::uint64_t bytes) {
  char text[32];
  if (bytes == UINT64_MAX) return "more than 18 EB";
  if (bytes >= 1000000000ull) std::snprintf(text, sizeof text, "%.1f GB", double(bytes) / 1e9);
  else std::snprintf(text, sizeof text, bytes >= 1000000 ? "%.0f MB" : "%.2f MB", double(bytes) / 1e6);
  return text;
}

namespace {

constexpr std::uint64_t kUnlimited = UINT64_MAX;


// A small file's text ("" when it cannot be read).
std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return in ? s.str() : "";
}

// A whole decimal number with nothing after it but white space; false for anything else.
bool parse_u64(const std::string& text, std::uint64_t& value) {
  std::size_t i = text.find_first_not_of(" \t");
  if (i == std::string::npos || text[i] < '0' || text[i] > '9') return false;
  value = 0;
  for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; i++) {
    if (__builtin_mul_overflow(value, 10u, &value) || __builtin_add_overflow(value, unsigned(text[i] - '0'), &value)) {
      return false;
    }
  }
  return text.find_first_not_of(" \t\n", i) == std::string::npos;
}

// "Key: value [kB]" or "key value" lines (meminfo, memory.stat): the value of `key`, in
// bytes where the line says kB.
bool find_value(const std::string& text, const std::string& key, std::uint64_t& value) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.compare(0, key.size(), key) != 0 || line.size() == key.size()) continue;
    std::string rest = line.substr(key.size());
    if (rest[0] != ':' && rest[0] != ' ') continue;
    if (rest[0] == ':') rest.erase(0, 1);
    const bool kb = rest.size() >= 3 && rest.compare(rest.size() - 3, 3, " kB") == 0;
    if (kb) rest.resize(rest.size() - 3);
    if (!parse_u64(rest, value)) return false;
    return !kb || !__builtin_mul_overflow(value, 1024u, &value);
  }
  return false;
}

// A memory cgroup of this process: its folder, and the folder its hierarchy is mounted at.
struct Cgroup {
  std::string dir, mount;
  bool v2;
};

// /proc/self/mountinfo's octal escapes (\040 for a space) undone.
std::string unescape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); i++) {
    const bool octal = s[i] == '\\' && i + 3 < s.size() && s.find_first_not_of("01234567", i + 1) >= i + 4;
    if (octal) {
      out += char((s[i + 1] - '0') * 64 + (s[i + 2] - '0') * 8 + (s[i + 3] - '0'));
      i += 3;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Where the cgroup v2 hierarchy and v1's memory hierarchy are mounted, and at which of
// their folders (a container sees its own cgroup as the root).
struct CgroupMount {
  std::string point = "", root = "/";
};
void find_cgroup_mounts(const std::string& root, CgroupMount& v2, CgroupMount& v1) {
  std::istringstream lines(read_text(root + "/proc/self/mountinfo"));
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream f(line);
    std::vector<std::string> field;
    for (std::string w; f >> w;) field.push_back(w);
    auto dash = std::find(field.begin(), field.end(), "-");
    if (field.size() < 5 || dash == field.end() || field.end() - dash < 4) continue;
    const std::string& type = dash[1];
    const std::string options = "," + dash[3] + ",";
    CgroupMount m{unescape(field[4]), unescape(field[3])};
    if (type == "cgroup2" && v2.point.empty()) v2 = m;
    if (type == "cgroup" && options.find(",memory,") != std::string::npos && v1.point.empty()) v1 = m;
  }
  if (v2.point.empty()) v2.point = "/sys/fs/cgroup";
  if (v1.point.empty()) v1.point = "/sys/fs/cgroup/memory";
}

std::vector<Cgroup> memory_cgroups(const std::string& root) {
  CgroupMount v2, v1;
  find_cgroup_mounts(root, v2, v1);
  std::vector<Cgroup> found;
  std::istringstream lines(read_text(root + "/proc/self/cgroup"));
  std::string line;
  while (std::getline(lines, line)) {  // "ID:controllers:path"
    const std::size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = "," + line.substr(a + 1, b - a - 1) + ",", path = line.substr(b + 1);
    const bool is_v2 = line.compare(0, a, "0") == 0 && controllers == ",,";
    if (!is_v2 && controllers.find(",memory,") == std::string::npos) continue;
    const CgroupMount& m = is_v2 ? v2 : v1;
    // The path below the mount's own folder; a path outside it is not seen from here.
    std::string below = path;
    if (m.root != "/") {
      const bool inside = path.compare(0, m.root.size(), m.root) == 0 &&
                          (path.size() == m.root.size() || path[m.root.size()] == '/');
      if (!inside) continue;
      below = path.substr(m.root.size());
    }
    found.push_back({m.point + below, m.point, is_v2});
  }
  return found;
}

// The smallest of limit - (usage - inactive_file) over the cgroup and each one above it,
// and which limit file gives it.
void cgroup_available(const std::string& root, const Cgroup& g, AvailableMemory& best) {
  const char* limit_file = g.v2 ? "memory.max" : "memory.limit_in_bytes";
  const char* usage_file = g.v2 ? "memory.current" : "memory.usage_in_bytes";
  const char* inactive_key = g.v2 ? "inactive_file" : "total_inactive_file";
  std::string dir = g.dir;
  while (dir.size() >= g.mount.size()) {
    std::uint64_t limit = 0, usage = 0, inactive = 0;
    // v1 writes "no limit" as a number near 2^63.
    if (parse_u64(read_text(root + dir + "/" + limit_file), limit) && limit < (std::uint64_t(1) << 60) &&
        parse_u64(read_text(root + dir + "/" + usage_file), usage)) {
      if (!find_value(read_text(root + dir + "/memory.stat"), inactive_key, inactive) || inactive > usage) inactive = 0;
      const std::uint64_t used = usage - inactive, left = limit > used ? limit - used : 0;
      if (left < best.bytes) {
        best.bytes = left;
        best.bound = "the cgroup's limit " + dir + "/" + limit_file + " (" + memory_size_words(limit) + ", " +
                     memory_size_words(used) + " of it in use)";
      }
    }
    const std::size_t slash = dir.find_last_of('/');
    if (slash == std::string::npos || dir.size() == g.mount.size()) break;
    dir.resize(slash);
  }
}

}  // namespace

AvailableMemory available_memory(const std::string& root, std::uint64_t address_space_limit) {
  AvailableMemory best;
  best.bytes = kUnlimited;
  std::uint64_t value = 0;
  if (find_value(read_text(root + "/proc/meminfo"), "MemAvailable", value)) {
    best.bytes = value, best.bound = "MemAvailable of /proc/meminfo";
  }
  for (const Cgroup& g : memory_cgroups(root)) cgroup_available(root, g, best);
  if (address_space_limit > 0) {
    // The address space this process already has: statm's first field, in pages.
    std::uint64_t size = 0;
    const std::string statm = read_text(root + "/proc/self/statm");
    if (!parse_u64(statm.substr(0, statm.find(' ')), size) ||
        __builtin_mul_overflow(size, std::uint64_t(::sysconf(_SC_PAGESIZE)), &size)) {
      if (!find_value(read_text(root + "/proc/self/status"), "VmSize", size)) size = 0;
    }
    const std::uint64_t left = address_space_limit > size ? address_space_limit - size : 0;
    const std::string words =
        "RLIMIT_AS (ulimit -v: " + memory_size_words(address_space_limit) + ", " + memory_size_words(size) + " of it in use)";
    if (left < best.bytes) best.bytes = left, best.bound = words;
    best.address_space = left, best.address_space_bound = words;
  }
  if (best.bytes == kUnlimited) {
    best.bytes = std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * std::uint64_t(::sysconf(_SC_PAGESIZE));
    best.bound = "the physical memory";
  }
  return best;
}

AvailableMemory available_memory() {
  const char* fake = std::getenv("PT_MEMORY_ROOT");
  struct rlimit as{};
  std::uint64_t limit = 0;
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) limit = std::uint64_t(as.rlim_cur);
  return available_memory(fake && *fake ? fake : "", limit);
}

std::uint64_t available_memory_bytes() { return available_memory().bytes; }

}  // namespace pt
