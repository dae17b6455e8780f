// CSV files of joint positions and of estimated derivatives, for offline
// filtering (`wbi estimate`). Input: a header `t,<joint names>` then one row
// per sample, t in seconds. Output: `t,dq0,…,dq(n-1),ddq0,…,ddq(n-1)`.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace wbi::estimation {

struct JointSamples {
  std::vector<std::string> joint_names;  // header names after `t`, in file order
  std::vector<double> t;                 // (samples) source time, s
  Eigen::MatrixXd q;                     // (samples × joints) positions, rad
};

struct JointDerivatives {
  std::vector<double> t;  // (samples) as in the input
  Eigen::MatrixXd dq;     // (samples × joints) rad/s
  Eigen::MatrixXd ddq;    // (samples × joints) rad/s²
};

// Parses CSV text; `source` (a file name) prefixes every error. Throws
// std::runtime_error "source:line: ..." naming the column on a bad field.
JointSamples parse_joint_csv(std::istream& in, const std::string& source);
// Reads a file; throws std::runtime_error when it cannot be opened or parsed.
JointSamples read_joint_csv(const std::filesystem::path& path);

void format_derivatives_csv(std::ostream& out, const JointDerivatives& derivatives);
// Throws std::runtime_error when the file cannot be written.
void write_derivatives_csv(const std::filesystem::path& path, const JointDerivatives& derivatives);

}  // namespace wbi::estimation
