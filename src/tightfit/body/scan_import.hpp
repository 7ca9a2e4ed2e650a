#pragma once
/// Body scans as they come: several surfaces in one file, files in
/// millimetres or centimetres, and (scan_repair.hpp) duplicate and non-manifold
/// elements, small holes, a million triangles. Every step reports what it did as a
/// warning (prefixed with the file's name).
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

/// The body surface of a scan (`mesh`, in the file's units), in metres: elements
/// repaired (repair_mesh_elements), small holes of every part filled
/// (fill_small_holes), the part that encloses the most volume kept (a warning lists
/// the others, as keep_largest_closed_component's), turned outwards if it was inside
/// out, scaled by `metres_per_file_unit` (times any "scale"; 0: guessed by
/// guess_units_to_metres). A warning says how many holes were filled and how large
/// (boundary length in m, edges, where). Throws InputError(source) when the kept part
/// still has a hole (too large to fill: the error gives its size, place and the limit),
/// or from the steps above.
TriMesh import_scan(const TriMesh& mesh, const std::string& source, double metres_per_file_unit,
                    std::vector<std::string>& warnings);

/// Metres per unit of "m", "cm" or "mm" (InputError otherwise).
double metres_per_unit(const std::string& units, const std::string& source);

}  // namespace tightfit
