#include "tightfit/garment/garment.hpp"

#include <algorithm>
#include <string>

#include "tightfit/common/error.hpp"

namespace tightfit {

Points2 Garment::rest_positions() const {
  Points2 rest(num_pattern_vertices(), 2);
  for (size_t k = 0; k < pattern.pieces.size(); ++k)
    rest.middleRows(topology->piece_offset[k], pattern.pieces[k].rest.rows()) =
        pattern.pieces[k].rest;
  return rest;
}

void Garment::set_rest_positions(const Points2& rest) {
  for (size_t k = 0; k < pattern.pieces.size(); ++k)
    pattern.pieces[k].rest =
        rest.middleRows(topology->piece_offset[k], pattern.pieces[k].rest.rows());
}

void Garment::set_pinned_vertices(std::vector<int> pinned) {
  for (int v : pinned)
    if (v < 0 || v >= num_garment_vertices())
      throw InputError("pattern", "pinned garment vertex " + std::to_string(v) + " out of range");
  std::sort(pinned.begin(), pinned.end());
  pinned.erase(std::unique(pinned.begin(), pinned.end()), pinned.end());
  auto next = std::make_shared<GarmentTopology>(*topology);
  next->pinned = std::move(pinned);
  topology = std::move(next);
}

Garment weld_pattern(Pattern pattern) {
  Garment g;
  g.topology = std::make_shared<const GarmentTopology>(weld_topology(pattern));
  g.pattern = std::move(pattern);
  return g;
}

}  // namespace tightfit
