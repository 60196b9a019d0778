// replace_file (common/app/replace_file.h): how every output file is written. A failed
// write leaves the old file whole, a link is written through at its target, devices and
// FIFOs are refused, long names get a short temporary name, and temporary files of killed
// runs are removed. Not part of the article: the machinery around its algorithms.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <limits>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/app/image_output.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"
#include "tests/support/cli_run.h"

namespace fs = std::filesystem;

namespace test_replace_file {  // this file's names: the unity build compiles it with others (tests/CMakeLists.txt)

namespace {

fs::path scratch() { return pt_test::scratch_dir("pt_replace_file"); }

void put(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

void replace_with(const fs::path& p, const std::string& text) {
  pt::replace_file(p.string(), {{text.data(), text.size()}}, "do something");
}

}  // namespace

TEST_CASE("replace_file: the new bytes replace the old file and keep its permission bits", "[reliability][output]") {
  const fs::path p = scratch() / "keep_mode.txt";
  put(p, "old");
  ::chmod(p.c_str(), 0600);
  replace_with(p, "new bytes");
  CHECK(pt_test::read_file(p) == "new bytes");
  struct stat st;
  REQUIRE(::stat(p.c_str(), &st) == 0);
  CHECK((st.st_mode & 0777) == 0600);
}

TEST_CASE("replace_file: a write that fails part-way leaves the old file whole and says why",
          "[reliability][output]") {
  // RLIMIT_FSIZE makes the kernel refuse writes past 4 KB (EFBIG), as a full disk refuses
  // them (ENOSPC); in a child, so that the limit and the ignored SIGXFSZ stay there.
  const fs::path p = scratch() / "short_write.bin";
  put(p, "the old file");
  pid_t child = ::fork();
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    struct rlimit limit = {4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::string big(1 << 16, 'x');
    try {
      replace_with(p, big);
    } catch (const pt::Error& e) {
      const std::string what = e.what();
      ::_exit(e.code() == pt::kExitOutput && what.find("File too large") != std::string::npos &&
                      what.find("old file is unchanged") != std::string::npos
                  ? 0
                  : 2);
    }
    ::_exit(1);  // no error: the short write was not seen
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(pt_test::read_file(p) == "the old file");
  // No temporary file is left beside it.
  int left = 0;
  for (const auto& e : fs::directory_iterator(p.parent_path())) left += e.path().filename().string().find("short_write.bin.") != std::string::npos;
  CHECK(left == 0);
}

TEST_CASE("replace_file: a symbolic link is written through at its target, and stays a link", "[reliability][output]") {
  const fs::path dir = scratch() / "links";
  fs::remove_all(dir);
  fs::create_directories(dir / "real");
  put(dir / "real" / "image.png", "old");
  fs::create_symlink("real/image.png", dir / "link.png");
  replace_with(dir / "link.png", "new");
  CHECK(fs::is_symlink(dir / "link.png"));
  CHECK(pt_test::read_file(dir / "real" / "image.png") == "new");
  // A dangling link makes its target, as cp does.
  fs::create_symlink("real/made.png", dir / "dangling.png");
  replace_with(dir / "dangling.png", "made");
  CHECK(pt_test::read_file(dir / "real" / "made.png") == "made");
  CHECK(fs::is_symlink(dir / "dangling.png"));
}

TEST_CASE("replace_file: a FIFO, a device or a folder as output is refused, and nothing replaces it",
          "[reliability][output]") {
  const fs::path fifo = scratch() / "pipe.png";
  fs::remove(fifo);
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  for (const std::string& path : {fifo.string(), std::string("/dev/null"), scratch().string()}) {
    INFO(path);
    try {
      pt::output_target(path, "--out");
      FAIL("accepted");
    } catch (const pt::Error& e) {
      CHECK(e.code() == pt::kExitOutput);
      CHECK(std::string(e.what()).find("not a file") != std::string::npos);
    }
  }
  CHECK(fs::is_fifo(fifo));
  // Through a link too.
  const fs::path link = scratch() / "to_null.png";
  fs::remove(link);
  fs::create_symlink("/dev/null", link);
  CHECK_THROWS_AS(pt::output_target(link.string(), "--out"), pt::Error);
  CHECK(fs::is_character_file("/dev/null"));
}

TEST_CASE("replace_file: a name of 255 bytes gets a temporary name the file system takes", "[reliability][output]") {
  for (std::size_t length : {200u, 240u, 248u, 255u}) {
    const std::string name = std::string(length - 4, 'n') + ".png";
    const fs::path p = scratch() / name;
    INFO(length);
    CHECK(fs::path(pt::temporary_path(p.string(), 4194304)).filename().string().size() <= 255);
    replace_with(p, "image");
    CHECK(pt_test::read_file(p) == "image");
    fs::remove(p);
  }
}

TEST_CASE("replace_file: temporary files of killed runs are removed, those of running ones kept",
          "[reliability][output]") {
  const fs::path dir = scratch() / "stale";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "render.exr";
  const long dead = pt_test::dead_pid(), alive = long(::getppid());
  put(pt::temporary_path(target.string(), dead), "killed");
  put(pt::temporary_path(target.string(), alive), "running");
  put(dir / (".render.exr.tmp" + std::to_string(dead) + ".exr"), "an earlier version's, killed");
  put(dir / (".other.exr.tmp" + std::to_string(dead) + ".exr"), "another output's");
  CHECK(pt::remove_stale_temporaries(target.string()) == 2);
  CHECK(fs::exists(pt::temporary_path(target.string(), alive)));
  CHECK(fs::exists(dir / (".other.exr.tmp" + std::to_string(dead) + ".exr")));
  CHECK_FALSE(fs::exists(pt::temporary_path(target.string(), dead)));
}

TEST_CASE("replace_file: same_file sees one file through links, hard links and dot-dot", "[reliability][output]") {
  const fs::path dir = scratch() / "same";
  fs::remove_all(dir);
  fs::create_directories(dir / "sub");
  put(dir / "a.exr", "a");
  fs::create_symlink("a.exr", dir / "link.exr");
  fs::create_hard_link(dir / "a.exr", dir / "hard.exr");
  CHECK(pt::same_file((dir / "a.exr").string(), (dir / "link.exr").string()));
  CHECK(pt::same_file((dir / "a.exr").string(), (dir / "hard.exr").string()));
  CHECK(pt::same_file((dir / "a.exr").string(), (dir / "sub" / ".." / "a.exr").string()));
  CHECK(pt::same_file((dir / "new.exr").string(), (dir / "sub" / ".." / "new.exr").string()));  // neither exists yet
  CHECK(pt::same_file((dir / "a.exr").string(), (dir / "not_yet" / ".." / "link.exr").string()));  // a folder made later
  CHECK_FALSE(pt::same_file((dir / "a.exr").string(), (dir / "b.exr").string()));
}

TEST_CASE("image output: a non-finite pixel is refused with exit 3 and the old image stays", "[reliability][output]") {
  const fs::path p = scratch() / "inf.exr";
  put(p, "old image");
  const pt::OutputFile out(p.string());
  std::vector<float> rgb(4 * 4 * 3, 0.5f);
  rgb[3 * 5 + 1] = std::numeric_limits<float>::infinity();
  pt::ImageMetadata meta;
  meta.stage = "test";
  try {
    out.write(rgb, 4, 4, meta);
    FAIL("written");
  } catch (const pt::Error& e) {
    CHECK(e.code() == pt::kExitBadScene);
    CHECK(std::string(e.what()).find("1 pixel is not a finite number (the first at x 1, y 1)") != std::string::npos);
  }
  CHECK(pt_test::read_file(p) == "old image");
}

}  // namespace test_replace_file
