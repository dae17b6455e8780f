// Eigen values as JSON, the way every `wbi model` report writes them: vectors as
// arrays, matrices as arrays of rows, an infinite limit as null (JSON has no inf).
#pragma once

#include <cmath>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace wbi::model_inspect::detail {

inline nlohmann::json limit_json(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

inline nlohmann::json vector_json(const Eigen::VectorXd& v) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    out.push_back(v[i]);
  }
  return out;
}

inline nlohmann::json rows_json(const Eigen::MatrixXd& m) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      row.push_back(m(r, c));
    }
    out.push_back(row);
  }
  return out;
}

}  // namespace wbi::model_inspect::detail
