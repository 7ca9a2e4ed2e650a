#include "tightfit/scene/pattern_export_options.hpp"

namespace tightfit {

PaperSize paper_size(Paper paper) {
  switch (paper) {
    case Paper::kA4:
      return {210.0, 297.0};
    case Paper::kLetter:
      return {215.9, 279.4};
  }
  return {210.0, 297.0};
}

}  // namespace tightfit
