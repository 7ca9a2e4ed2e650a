#include "tightfit/common/element_matrices.hpp"

#include <stdexcept>
#include <string>

namespace tightfit {

ElementMatrices::ElementMatrices(int vertices_per_element, std::vector<int> vertices)
    : vertices_per_element_(vertices_per_element), vertices_(std::move(vertices)) {
  if (vertices_per_element < 1)
    throw std::invalid_argument("ElementMatrices: " + std::to_string(vertices_per_element) +
                                " vertices per element");
  if (vertices_.size() % static_cast<std::size_t>(vertices_per_element) != 0)
    throw std::invalid_argument("ElementMatrices: " + std::to_string(vertices_.size()) +
                                " vertex ids are not a whole number of elements of " +
                                std::to_string(vertices_per_element));
  num_elements_ = static_cast<std::int64_t>(vertices_.size()) / vertices_per_element;
  values_ = std::make_unique_for_overwrite<double[]>(
      static_cast<std::size_t>(num_elements_ * matrix_values()));
}

}  // namespace tightfit
