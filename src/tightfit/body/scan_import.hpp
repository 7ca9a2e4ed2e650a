#pragma once
/// Body scans as they come (issue 13): several surfaces in one file, and files in
/// millimetres or centimetres. Both steps report what they did as warnings.
#include <string>
#include <vector>

#include "tightfit/geometry/mesh.hpp"

namespace tightfit {

/// The largest closed component (by enclosed volume) of `mesh`. When the file holds more
/// than one component, a warning lists the others (faces, whether closed, area in the
/// file's units). Throws InputError (source `source`) when no component is closed.
TriMesh keep_largest_closed_component(const TriMesh& mesh, const std::string& source,
                                      std::vector<std::string>& warnings);

/// The factor from the file's units to metres guessed from the body's largest extent L
/// (bounding box, in the file's units), for a human body or body part (0.05-3 m):
///   L <= 3: metres (1);  3 < L < 50: centimetres (0.01);  300 < L <= 3000: millimetres
///   (0.001); with a warning saying so. 50 <= L <= 300 could be centimetres (a whole
///   body) or millimetres (a head, a forearm), L < 0.05 or L > 3000 is no body in any
///   unit: InputError (source `source`) asking for "units".
double guess_units_to_metres(const TriMesh& mesh, const std::string& source,
                             std::vector<std::string>& warnings);

/// Metres per unit of "m", "cm" or "mm" (InputError otherwise).
double metres_per_unit(const std::string& units, const std::string& source);

}  // namespace tightfit
