#include "wbi/estimation/trajectory_csv.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace wbi::estimation {
namespace {

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) {
    return "";
  }
  const auto end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (true) {
    const auto comma = line.find(',', begin);
    fields.push_back(trim(line.substr(begin, comma - begin)));
    if (comma == std::string::npos) {
      return fields;
    }
    begin = comma + 1;
  }
}

double parse_number(const std::string& field, const std::string& where) {
  double value = 0.0;
  const char* first = field.data();
  const char* last = first + field.size();
  if (!field.empty() && *first == '+') {
    ++first;  // from_chars does not accept a leading '+'
  }
  const auto [end, ec] = std::from_chars(first, last, value);
  if (field.empty() || ec != std::errc() || end != last) {
    throw std::runtime_error(where + ": '" + field + "' is not a number");
  }
  return value;
}

}  // namespace

JointSamples parse_joint_csv(std::istream& in, const std::string& source) {
  JointSamples samples;
  std::string line;
  std::size_t line_number = 0;
  std::vector<std::vector<double>> rows;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++line_number;
    if (trim(line).empty()) {
      continue;  // blank lines, e.g. at the end of the file
    }
    const std::string at_line = source + ":" + std::to_string(line_number);
    const std::vector<std::string> fields = split_fields(line);
    if (!have_header) {
      if (fields[0] != "t") {
        throw std::runtime_error(at_line + ": the header must start with column 't', found '" +
                                 fields[0] + "'");
      }
      if (fields.size() < 2) {
        throw std::runtime_error(at_line + ": the header names no joint column after 't'");
      }
      for (std::size_t c = 1; c < fields.size(); ++c) {
        if (fields[c].empty()) {
          throw std::runtime_error(at_line + ": column " + std::to_string(c + 1) +
                                   " has an empty name");
        }
      }
      samples.joint_names.assign(fields.begin() + 1, fields.end());
      have_header = true;
      continue;
    }
    if (fields.size() != samples.joint_names.size() + 1) {
      throw std::runtime_error(at_line + ": expected " +
                               std::to_string(samples.joint_names.size() + 1) +
                               " columns as in the header, found " + std::to_string(fields.size()));
    }
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const std::string name = c == 0 ? std::string("t") : samples.joint_names[c - 1];
      row[c] = parse_number(fields[c],
                            at_line + ": column " + std::to_string(c + 1) + " (" + name + ")");
    }
    if (!std::isfinite(row[0])) {
      throw std::runtime_error(at_line + ": column 1 (t): time must be finite");
    }
    rows.push_back(std::move(row));
  }
  if (!have_header) {
    throw std::runtime_error(source + ": empty file, expected a header 't,<joint columns>'");
  }
  const auto joints = static_cast<Eigen::Index>(samples.joint_names.size());
  samples.q.resize(static_cast<Eigen::Index>(rows.size()), joints);
  samples.t.reserve(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    samples.t.push_back(rows[r][0]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      samples.q(static_cast<Eigen::Index>(r), j) = rows[r][static_cast<std::size_t>(j) + 1];
    }
  }
  return samples;
}

JointSamples read_joint_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error(path.string() + ": cannot open for reading");
  }
  return parse_joint_csv(in, path.string());
}

namespace {

// Shortest text that reads back to the same double.
void put_number(std::ostream& out, double value) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  out.write(buffer.data(), end - buffer.data());
}

}  // namespace

void format_derivatives_csv(std::ostream& out, const JointDerivatives& derivatives) {
  const Eigen::Index joints = derivatives.dq.cols();
  out << "t";
  for (Eigen::Index j = 0; j < joints; ++j) {
    out << ",dq" << j;
  }
  for (Eigen::Index j = 0; j < joints; ++j) {
    out << ",ddq" << j;
  }
  out << "\n";
  for (std::size_t r = 0; r < derivatives.t.size(); ++r) {
    const auto row = static_cast<Eigen::Index>(r);
    put_number(out, derivatives.t[r]);
    for (Eigen::Index j = 0; j < joints; ++j) {
      out << ',';
      put_number(out, derivatives.dq(row, j));
    }
    for (Eigen::Index j = 0; j < joints; ++j) {
      out << ',';
      put_number(out, derivatives.ddq(row, j));
    }
    out << "\n";
  }
}

void write_derivatives_csv(const std::filesystem::path& path, const JointDerivatives& derivatives) {
  std::ofstream out(path);
  if (!out) {
    throw std::runtime_error(path.string() + ": cannot open for writing");
  }
  format_derivatives_csv(out, derivatives);
  out.flush();
  if (!out) {
    throw std::runtime_error(path.string() + ": write failed");
  }
}

}  // namespace wbi::estimation
