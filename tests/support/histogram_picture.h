// The picture of a chi-square test (chi2.h) for a student to look at: the sampler's
// histogram beside what its pdf expects, bin by bin, and where they disagree. The labs'
// sampler tests write one for each hemisphere sampler (docs/labs/lab2.md, lab3.md).
// Tooling for the tests, not part of the article.
#pragma once

#include <string>

#include "tests/support/chi2.h"

namespace pt::test {

// Writes a PNG of three panels, each a grid of the bins (rows: cos theta from +1 at the top
// to -1 at the bottom, columns: phi from 0 to 2 pi): the samples counted in each bin, the
// count the pdf expects there (both on one grey scale, white the largest expected count),
// and their difference in standard deviations, (observed - expected) / sqrt(expected),
// red where there are too many samples and blue where too few, full colour at 5.
// false: `why` says why in one line.
bool write_histogram_picture(const std::string& path, const Chi2Result& r, std::string& why);

// Where the sampler tests put their pictures: $PT_TEST_PICTURES, or test_pictures/ in the
// current folder (ctest runs pt_tests in build/tests). The folder is made if need be.
std::string test_picture_path(const std::string& name);

}  // namespace pt::test
