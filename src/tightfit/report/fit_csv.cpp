#include "tightfit/report/fit_csv.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

#include "tightfit/common/atomic_file.hpp"
#include "tightfit/common/types.hpp"

namespace tightfit {

void write_fit_csv(const std::filesystem::path& file, const Garment& garment,
                   const std::vector<ClothElementFit>& elements, const VecX& pressure_pa,
                   const VecX* sliding_excess_n) {
  const auto faces = static_cast<Eigen::Index>(elements.size());
  if (pressure_pa.size() != faces || (sliding_excess_n && sliding_excess_n->size() != faces))
    throw std::invalid_argument("write_fit_csv: one value per garment face is needed");
  std::string text =
      "face,piece,area_m2,stretch_max,stretch_min,stretch_course,stretch_wale,regime,"
      "tension_max_n_per_m,pressure_pa,pressure_mmhg";
  text += sliding_excess_n ? ",sliding_excess_n\n" : "\n";
  char row[512];
  for (Eigen::Index f = 0; f < faces; ++f) {
    const ClothElementFit& e = elements[static_cast<std::size_t>(f)];
    const int piece = garment.topology->triangle_piece[static_cast<std::size_t>(f)];
    std::string name = garment.pattern.pieces[static_cast<std::size_t>(piece)].name;
    if (name.find_first_of(",\"\n") != std::string::npos) {
      std::string quoted = "\"";
      for (char c : name) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
      name = quoted + "\"";
    }
    std::snprintf(row, sizeof row, ",%.9g,%.9g,%.9g,%.9g,%.9g,%s,%.9g,%.9g,%.9g", e.deformed_area,
                  e.stretch[0], e.stretch[1], e.grain_stretch[0], e.grain_stretch[1],
                  regime_name(e.regime), e.principal_tension[0], pressure_pa[f],
                  pressure_pa[f] / kPascalPerMmHg);
    text += std::to_string(f) + "," + name + row;
    if (sliding_excess_n) {
      std::snprintf(row, sizeof row, ",%.9g", (*sliding_excess_n)[f]);
      text += row;
    }
    text += "\n";
  }
  write_text_atomically(file, text);
}

}  // namespace tightfit
