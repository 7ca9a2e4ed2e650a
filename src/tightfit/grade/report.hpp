#pragma once
/// grade.html: the grading report in the pattern maker's language, one self-contained
/// page without scripts: the bodies with their status (and error), objective ratio,
/// iterations and times; per size the stretch and pressure statistics; the nest of every
/// piece (all sizes on top of each other, one colour per size, aligned as the nest says)
/// and the size-to-size change of every seam length in mm.
#include <filesystem>

#include "tightfit/grade/summary.hpp"
#include "tightfit/patterns/nest.hpp"

namespace tightfit {

/// Writes grade.html (atomically). `nest` is null when no body is done.
void write_grade_report(const std::filesystem::path& file, const GradeSummary& summary,
                        const Nest* nest);

}  // namespace tightfit
