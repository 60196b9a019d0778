// pt_merge: adds up the parts of one render (the contract (README.md), "Parts, merging and
// comparing"): each part is an .exr that a stage wrote with --out after rendering some
// --samples FIRST:COUNT range; the merge is the render of all their samples, bit for bit
// where the parts split at the pass ends of one run, else equal to float rounding. Parts of
// another scene, stage, option set or seed, and samples held twice, are refused, as are an
// --out that is one of the parts and a part whose header or film is damaged or was edited
// (film_file.h). Not in the article: its estimators are sums of independent samples, which
// makes this exact.
//   pt_merge --out MERGED.exr PART.exr...
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/app/app.h"
#include "common/app/film_file.h"
#include "common/app/image_output.h"
#include "common/app/replace_file.h"
#include "common/base/error.h"

namespace {

int run(int argc, char** argv) {
  std::string out_path;
  std::vector<std::string> inputs;
  CLI::App app("pt_merge: adds up the .exr parts of one render (the stages' --samples FIRST:COUNT)", "pt_merge");
  app.add_option("--out", out_path, "the merged image (.exr, itself a part that can be merged again)")->required();
  app.add_option("parts", inputs, "the parts: .exr files written by a stage's --out")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", app.help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    throw pt::Error(pt::kExitBadOption, what.substr(0, what.find('\n')) +
                                            "; usage: pt_merge --out MERGED.exr PART.exr... (pt_merge --help)");
  }
  if (!pt::OutputFile::is_exr(out_path)) {
    throw pt::Error(pt::kExitBadOption, "--out '" + out_path + "' is not an .exr: the merge is a part too; name it *.exr");
  }
  // The merge must not replace a part: --out may name one by another spelling, through a
  // symbolic link or as a hard link, which the same device and inode reveal.
  for (const std::string& part : inputs) {
    if (pt::same_file(out_path, part)) {
      throw pt::Error(pt::kExitBadOption, "--out '" + out_path + "' is the same file as the part '" + part +
                                              "': the merge would replace it; write the merge to a new file");
    }
  }
  const pt::OutputFile out(out_path);  // checked before reading the parts
  std::vector<pt::FilmPart> parts;
  for (const std::string& path : inputs) parts.push_back(pt::read_film_part(path));
  std::vector<std::string> notes;
  const std::size_t count = parts.size();
  pt::FilmPart merged = pt::merge_film_parts(std::move(parts), notes);
  for (const std::string& note : notes) std::fprintf(stderr, "pt_merge: %s\n", note.c_str());

  pt::ImageMetadata meta;
  meta.stage = merged.id.stage;
  meta.backend = merged.backend;
  meta.scene = merged.scene;
  meta.spp = merged.film.spp();
  meta.seed = merged.id.seed;
  meta.film = &merged.film;
  meta.identity = merged.id;
  meta.ranges = merged.ranges;
  meta.keep_halves = merged.kept_halves;  // where the parts kept theirs (--keep-halves)
  out.write(merged.film.mean_rgb(), merged.film.width(), merged.film.height(), meta);
  const pt::Film& f = merged.film;
  std::printf("pt_merge: %zu parts, %s, %dx%d, %llu spp, samples %s", count, merged.id.stage.c_str(), f.width(),
              f.height(), (unsigned long long)f.spp(), pt::format_ranges(merged.ranges).c_str());
  if (f.spp() >= 2) {
    std::printf(", estimated per-pixel relative error %.2g, image-mean error %.2g", f.per_pixel_relative_error(),
                f.relative_standard_error());
  }
  std::printf(" -> %s\n", out_path.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return pt::run_guarded("pt_merge", [&] { return run(argc, argv); });
}
