// wbi estimate: offline joint velocity/acceleration estimation from a CSV of
// joint positions. The work is in wbi::estimation; this file maps the command line.
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../options.hpp"
#include "../verb.hpp"
#include "wbi/estimation/estimator_factory.hpp"
#include "wbi/estimation/offline_filter.hpp"
#include "wbi/estimation/trajectory_csv.hpp"

namespace wbi::cli {
namespace {

std::string joined_method_names() {
  std::string out;
  for (const auto& name : estimation::method_names()) {
    out += (out.empty() ? "" : " ") + name;
  }
  return out;
}

// Every method's parameters as options; each name once (the stream parameters are shared).
// The help line ends with the method(s) and the default, e.g. "[kalman; default 3]".
void declare_method_options(Options& options, std::set<std::string>& names) {
  for (const auto& method : estimation::methods()) {
    for (const auto& spec : method.parameters) {
      if (!names.insert(spec.name).second) {
        continue;
      }
      bool shared = true;
      for (const auto& other : estimation::methods()) {
        bool found = false;
        for (const auto& other_spec : other.parameters) {
          found = found || other_spec.name == spec.name;
        }
        shared = shared && found;
      }
      std::ostringstream help;
      help << spec.help << " [" << (shared ? std::string("all methods") : method.name)
           << "; default " << spec.default_value << "]";
      options.option(spec.name, spec.metavar, help.str());
    }
  }
}

std::string warning_text(const estimation::StampCounters& counters) {
  std::string text;
  const auto add = [&](std::uint64_t count, const char* what) {
    if (count > 0) {
      text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + what;
    }
  };
  add(counters.duplicated, "rows with a duplicated stamp (ignored)");
  add(counters.out_of_order, "rows with an older stamp (ignored)");
  add(counters.non_finite, "rows with a non-finite position (ignored)");
  add(counters.dropped, "missing samples");
  add(counters.gaps, "gaps longer than max-gap (estimator restarted)");
  return text;
}

}  // namespace

int run_estimate(Args args) {
  Options options("wbi estimate --method NAME --input IN.csv --output OUT.csv [method options]",
                  "Estimates joint velocities and accelerations offline. IN.csv has a header "
                  "'t,<joint columns>' (t in seconds) and one row per sample; OUT.csv gets "
                  "'t,dq0,...,dq(n-1),ddq0,...,ddq(n-1)', one row per input row. Each method "
                  "takes only its own options (in brackets below). Stamp anomalies (duplicated, "
                  "older or missing rows) are counted and reported as one warning on stderr.");
  options.flag("list", "print the method names, whitespace-separated, and exit")
      .option("method", "NAME", "estimation method: " + joined_method_names())
      .option("input", "IN.csv", "joint positions to filter")
      .option("output", "OUT.csv", "where to write the estimates");
  std::set<std::string> parameter_names;
  declare_method_options(options, parameter_names);
  options.example("wbi estimate --list", "the methods");
  options.example(
      "wbi estimate --method split-kalman --input estimation/examples/encoder.csv "
      "--output dq.csv",
      "two arm joints read by encoders at 1 kHz (a file of the repository)");
  if (!options.parse(args)) {
    return kExitOk;
  }
  if (options.has("list")) {
    std::cout << joined_method_names() << "\n";
    return kExitOk;
  }
  const std::string method = options.get("method");
  const std::string input = options.get("input");
  const std::string output = options.get("output");

  estimation::Parameters given;
  for (const auto& name : parameter_names) {
    if (options.has(name)) {
      given[name] = options.get_double(name);
    }
  }
  const estimation::JointSamples samples = estimation::read_joint_csv(input);
  std::unique_ptr<estimation::DerivativeEstimator> estimator;
  try {
    estimator = estimation::make_estimator(
        method, static_cast<Eigen::Index>(samples.joint_names.size()), given);
  } catch (const std::invalid_argument& error) {
    throw UsageError(error.what());  // unknown method, option or value
  }
  const estimation::JointDerivatives derivatives =
      estimation::estimate_offline(*estimator, samples);
  estimation::write_derivatives_csv(output, derivatives);
  if (const std::string warning = warning_text(estimator->stamp_counters()); !warning.empty()) {
    std::cerr << "wbi estimate: warning: " << input << ": " << warning << "\n";
  }
  return kExitOk;
}

}  // namespace wbi::cli
