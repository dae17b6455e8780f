// A small declarative option parser for the verbs: flags, valued options and
// positionals, with --help generated from the declarations.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "verb.hpp"

namespace wbi::cli {

// A command of --help's closing examples, and what it does (may be empty).
struct Example {
  std::string command;
  std::string what;
};

// "Examples:" (or "Example:"), then each command under a comment line saying
// what it does: the last section of every --help, so that it ends with a command.
std::string examples_text(const std::vector<Example>& examples);

class Options {
 public:
  // usage: e.g. "wbi model info URDF [options]"; summary: one paragraph.
  Options(std::string usage, std::string summary);

  // --name (no value). help: one line.
  Options& flag(const std::string& name, const std::string& help);
  // --name VALUE (also --name=VALUE). default_value empty: optional with no default.
  Options& option(const std::string& name, const std::string& metavar, const std::string& help,
                  std::optional<std::string> default_value = std::nullopt);
  // A positional argument, in order of declaration.
  Options& positional(const std::string& name, const std::string& help, bool required = true);
  // Accept any number of extra positionals after the declared ones.
  Options& rest(const std::string& name, const std::string& help);
  // A command for the examples that end --help (every verb has at least one).
  Options& example(const std::string& command, const std::string& what = "");

  // Parses args. Returns false when --help was given (help already printed to stdout).
  // Throws UsageError naming the offending argument otherwise.
  bool parse(Args args);

  bool has(const std::string& name) const;         // flag given, or option/positional present
  std::string get(const std::string& name) const;  // throws UsageError when absent
  std::optional<std::string> get_optional(const std::string& name) const;
  double get_double(const std::string& name) const;  // throws UsageError when not a number
  long get_int(const std::string& name) const;
  const std::vector<std::string>& rest_values() const { return rest_values_; }

  std::string help_text() const;

 private:
  struct Spec {
    std::string name;
    std::string metavar;  // empty for flags
    std::string help;
    std::optional<std::string> default_value;
  };
  struct Positional {
    std::string name;
    std::string help;
    bool required;
  };

  const Spec* find(const std::string& name) const;

  std::string usage_;
  std::string summary_;
  std::vector<Spec> specs_;
  std::vector<Positional> positionals_;
  std::optional<Positional> rest_;
  std::vector<Example> examples_;
  std::map<std::string, std::string> values_;
  std::vector<std::string> rest_values_;
};

}  // namespace wbi::cli
