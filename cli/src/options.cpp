#include "options.hpp"

#include <charconv>
#include <iostream>
#include <sstream>

namespace wbi::cli {

std::string examples_text(const std::vector<Example>& examples) {
  std::string text = examples.size() == 1 ? "Example:\n" : "Examples:\n";
  for (const auto& example : examples) {
    text += example.what.empty() ? "" : "  # " + example.what + "\n";
    text += "  " + example.command + "\n";
  }
  return text;
}

Options::Options(std::string usage, std::string summary)
    : usage_(std::move(usage)), summary_(std::move(summary)) {}

Options& Options::flag(const std::string& name, const std::string& help) {
  specs_.push_back({name, "", help, std::nullopt});
  return *this;
}

Options& Options::option(const std::string& name, const std::string& metavar,
                         const std::string& help, std::optional<std::string> default_value) {
  specs_.push_back({name, metavar, help, std::move(default_value)});
  return *this;
}

Options& Options::positional(const std::string& name, const std::string& help, bool required) {
  positionals_.push_back({name, help, required});
  return *this;
}

Options& Options::rest(const std::string& name, const std::string& help) {
  rest_ = Positional{name, help, false};
  return *this;
}

Options& Options::example(const std::string& command, const std::string& what) {
  examples_.push_back({command, what});
  return *this;
}

const Options::Spec* Options::find(const std::string& name) const {
  for (const auto& spec : specs_) {
    if (spec.name == name) {
      return &spec;
    }
  }
  return nullptr;
}

bool Options::parse(Args args) {
  std::size_t next_positional = 0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    // -o is --output wherever a verb has one (record, render, model mjcf).
    const std::string arg =
        args[i] == "-o" && find("output") != nullptr ? std::string("--output") : args[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << help_text();
      return false;
    }
    if (arg.size() > 2 && arg.rfind("--", 0) == 0) {
      std::string name = arg.substr(2);
      std::optional<std::string> inline_value;
      if (const auto eq = name.find('='); eq != std::string::npos) {
        inline_value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      const Spec* spec = find(name);
      if (spec == nullptr) {
        throw UsageError("unknown option --" + name);
      }
      if (spec->metavar.empty()) {
        if (inline_value) {
          throw UsageError("option --" + name + " takes no value");
        }
        values_[name] = "";
      } else if (inline_value) {
        values_[name] = *inline_value;
      } else {
        if (i + 1 >= args.size()) {
          throw UsageError("option --" + name + " needs a value " + spec->metavar);
        }
        values_[name] = args[++i];
      }
      continue;
    }
    if (next_positional < positionals_.size()) {
      values_[positionals_[next_positional++].name] = arg;
    } else if (rest_) {
      rest_values_.push_back(arg);
    } else {
      throw UsageError("unexpected argument '" + arg + "'");
    }
  }
  for (std::size_t p = next_positional; p < positionals_.size(); ++p) {
    if (positionals_[p].required) {
      throw UsageError("missing argument " + positionals_[p].name);
    }
  }
  for (const auto& spec : specs_) {
    if (spec.default_value && values_.count(spec.name) == 0) {
      values_[spec.name] = *spec.default_value;
    }
  }
  return true;
}

bool Options::has(const std::string& name) const { return values_.count(name) != 0; }

std::string Options::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) {
    throw UsageError("missing " +
                     (find(name) != nullptr ? "option --" + name : "argument " + name));
  }
  return it->second;
}

std::optional<std::string> Options::get_optional(const std::string& name) const {
  const auto it = values_.find(name);
  return it == values_.end() ? std::nullopt : std::optional<std::string>(it->second);
}

double Options::get_double(const std::string& name) const {
  const std::string text = get(name);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw UsageError("--" + name + " expects a number, got '" + text + "'");
  }
  return value;
}

long Options::get_int(const std::string& name) const {
  const std::string text = get(name);
  long value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw UsageError("--" + name + " expects an integer, got '" + text + "'");
  }
  return value;
}

std::string Options::help_text() const {
  std::ostringstream out;
  out << "usage: " << usage_ << "\n\n" << summary_ << "\n";
  if (!positionals_.empty() || rest_) {
    out << "\narguments:\n";
    for (const auto& p : positionals_) {
      out << "  " << p.name << (p.required ? "" : " (optional)") << "\n      " << p.help << "\n";
    }
    if (rest_) {
      out << "  " << rest_->name << "...\n      " << rest_->help << "\n";
    }
  }
  out << "\noptions:\n  -h, --help\n      show this help and exit\n";
  for (const auto& spec : specs_) {
    out << "  --" << spec.name << (spec.metavar.empty() ? "" : " " + spec.metavar) << "\n      "
        << spec.help;
    if (spec.default_value && !spec.default_value->empty()) {
      out << " (default: " << *spec.default_value << ")";
    }
    out << "\n";
  }
  if (!examples_.empty()) {
    out << "\n" << examples_text(examples_);
  }
  return out.str();
}

}  // namespace wbi::cli
