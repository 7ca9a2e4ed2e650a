#pragma once
/// Checks that a Pattern can be exported: every index in range, seams well formed.
#include <string>

#include "tightfit/garment/pattern.hpp"
#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

/// Throws InputError(source, ...) naming the piece/seam and the problem when:
/// a piece has an empty or duplicate name, fewer than 3 rest vertices, no triangles,
/// non-finite positions, triangle/boundary/corner indices out of range, a boundary
/// loop with fewer than 3 or repeated vertices or that is not counter-clockwise
/// (signed area ≤ 0), a corner not on the boundary, a zero grain direction; a seam or
/// pinned boundary refers to a missing piece, has out-of-range vertices or vertices off
/// the boundary, is not a run of consecutive boundary vertices; the two sides of a
/// seam have different counts or fewer than 2 vertices.
void validate_pattern(const Pattern& pattern, const std::string& source);

/// Throws InputError(source, ...) for bad options: negative allowance, mitre limit
/// < 1, negative notch spacing, overlap/margin not leaving room on the page,
/// non-positive quantities, negative notch depth, double-notch gap or truing tolerance,
/// `seam_allowances` naming no seam/pinned boundary, `seam_notch_styles` or
/// `seam_last_end_up` naming no seam, or `piece_notes` naming no piece.
void validate_export_options(const Pattern& pattern, const PatternExportOptions& options,
                             const std::string& source);

}  // namespace tightfit
