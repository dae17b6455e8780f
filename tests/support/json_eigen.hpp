// Eigen vectors and matrices read back from the JSON that `wbi model eval` and
// wbi::model_inspect write (rows of numbers), for the tests that check them.
#pragma once

#include <cstddef>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace wbi::test {

inline Eigen::MatrixXd matrix_of_json(const nlohmann::json& rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(rows[0].size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][c].get<double>();
    }
  }
  return m;
}

inline Eigen::VectorXd vector_of_json(const nlohmann::json& v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) {
    x[static_cast<Eigen::Index>(i)] = v[i].get<double>();
  }
  return x;
}

}  // namespace wbi::test
