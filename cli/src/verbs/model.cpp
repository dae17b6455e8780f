// `wbi model info|eval|bench|mjcf`: inspect a URDF, evaluate the model at a state
// given as JSON, time the algorithms, write it as MJCF. This file parses the
// options and prints; the work is in wbi::model_inspect (model_service/inspect),
// wbi::model, wbi::mjcf and, for --robot-config, wbi::mujoco_sim's robot_mjcf.
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/backend.hpp>
#include <wbi/model/urdf.hpp>
#include <wbi/model_inspect/algorithm_timing.hpp>
#include <wbi/model_inspect/info_report.hpp>
#include <wbi/model_inspect/mjcf_export.hpp>
#include <wbi/model_inspect/state_evaluation.hpp>
#include <wbi/mujoco_sim/robot_mjcf.hpp>
#include <wbi/robot_config/robot_config.hpp>

#include "../options.hpp"
#include "../subcommands.hpp"
#include "verbs.hpp"

namespace wbi::cli {

int run_model(Args args);

namespace {

namespace wm = wbi::model;
namespace inspect = wbi::model_inspect;

const char* const kModelNotes =
    "Each reads a URDF (the project's robots: models/). eval and bench take\n"
    "--backend wbi|dart: the dynamics library that computes (default wbi). info, eval\n"
    "and bench take --armature JOINT=VALUE,...: per-joint rotor inertia (default 0).\n";

// The project's arm (models/arm7.urdf: fixed to `world`, joint_1 … joint_7, frame ee_link).
const char* const kInfoExample = "wbi model info models/arm7.urdf";
const char* const kEvalExample =
    "echo '{\"q\": [0, 0.4, 0, 1.6, 0, 1.14, 0]}' | wbi model eval models/arm7.urdf --state -";
const char* const kBenchExample = "wbi model bench models/arm7.urdf";
const char* const kMjcfExample = "wbi model mjcf models/arm7.urdf -o arm7.xml";

// "a,b,c" → {"a","b","c"}
std::vector<std::string> split_list(const std::string& text, const std::string& option = "joints",
                                    const std::string& what = "joint") {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    if (item.empty()) {
      throw UsageError("--" + option + ": empty " + what + " name in '" + text + "'");
    }
    out.push_back(item);
  }
  if (out.empty()) {
    throw UsageError("--" + option + ": no " + what + " names given");
  }
  return out;
}

// "a=0.1,b=2e-3" → {a: 0.1, b: 0.002}; the values are checked by the loader.
std::map<std::string, double> parse_armature(const std::string& text) {
  std::map<std::string, double> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError("--armature: '" + item + "' is not JOINT=VALUE");
    }
    const std::string value = item.substr(eq + 1);
    std::size_t used = 0;
    double number = 0.0;
    try {
      number = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (value.empty() || used != value.size()) {
      throw UsageError("--armature: the value of '" + item.substr(0, eq) + "' is not a number: '" +
                       value + "'");
    }
    if (!out.emplace(item.substr(0, eq), number).second) {
      throw UsageError("--armature: joint '" + item.substr(0, eq) + "' given twice");
    }
  }
  if (out.empty()) {
    throw UsageError("--armature: no JOINT=VALUE given");
  }
  return out;
}

const char* const kArmatureHelp =
    "rotor inertia reflected through the gear ratio, per joint: JOINT=VALUE,... [kg m^2 or kg] "
    "(added to the diagonal of M, MuJoCo's convention; default 0)";

wm::LoadOptions load_options(const Options& opts) {
  wm::LoadOptions options;
  options.fixed_base = opts.has("fixed-base");
  if (const auto joints = opts.get_optional("joints")) {
    options.joints = split_list(*joints);
  }
  if (const auto armature = opts.get_optional("armature")) {
    options.armature = parse_armature(*armature);
  }
  return options;
}

wm::Model load(const Options& opts) {
  try {
    return wm::load_urdf_file(opts.get("URDF"), load_options(opts));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

const char* const kBackendHelp =
    "dynamics library that computes: wbi (the project's own) or dart (DART 6, when built)";

// The model behind the backend named by --backend.
std::unique_ptr<wm::ModelBackend> load_backend(const Options& opts) {
  const std::string name = opts.get("backend");
  try {
    wm::check_model_backend_name(name);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  try {
    return wm::make_model_backend(name, opts.get("URDF"), load_options(opts));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

// ---------------------------------------------------------------- info

int run_info(Args args) {
  Options opts(
      "wbi model info URDF [--fixed-base] [--joints a,b,...] [--armature j=v,...] [--json]",
      "Print the model built from a URDF: base kind, joints in order with their limits\n"
      "and armature, bodies after lumping fixed joints, frames (every link) and the total "
      "mass.");
  opts.positional("URDF", "the robot description (.urdf)")
      .flag("fixed-base",
            "fix the root link to the world (default: free-floating, unless the root is a massless "
            "'world')")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order); lock the "
              "rest at 0")
      .option("armature", "LIST", kArmatureHelp)
      .flag("json", "print JSON instead of text");
  opts.example(kInfoExample, "the project's 7-joint arm")
      .example("wbi model info models/humanoid.urdf --joints l_hip_pitch,l_knee,l_ankle_pitch",
               "a reduced humanoid: three joints of its left leg, the others locked at 0")
      .example("wbi model info models/humanoid.urdf --json", "as JSON");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const wm::Model m = load(opts);
  if (opts.has("json")) {
    std::cout << inspect::info_json(m).dump(2) << "\n";
  } else {
    inspect::write_info_text(std::cout, m);
  }
  return kExitOk;
}

// ---------------------------------------------------------------- eval

int run_eval(Args args) {
  Options opts(
      "wbi model eval URDF --state FILE|- [--fixed-base] [--joints a,b,...] [--armature j=v,...]",
      "Evaluate the model at a state read as JSON and print the results as JSON.\n"
      "State keys (all optional): q, dq (in the order of 'joints' when given, else the model's),\n"
      "base_position [3], base_quaternion [w,x,y,z], base_velocity [6: linear, angular, world "
      "axes],\n"
      "gravity [3] (default [0,0,-9.81]), frames [names], joints [every joint, in the caller's "
      "order].\n"
      "Output keys: backend, joints, mass_matrix, bias_forces, gravity_forces, total_mass, com,\n"
      "centroidal_momentum, frames {name: {transform 4x4, jacobian 6x(n+6), dJnu [6]}}.\n"
      "Sizes are n+6 for a free-floating model, n with a fixed base; matrices are arrays of rows.");
  opts.positional("URDF", "the robot description (.urdf)")
      .option("state", "FILE", "the state as JSON, '-' for standard input")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order); lock the "
              "rest at 0")
      .option("armature", "LIST", kArmatureHelp)
      .option("backend", "NAME", kBackendHelp, "wbi");
  opts.example(kEvalExample, "the arm at its home posture (models/README.md)")
      .example("echo '{\"frames\": [\"ee_link\"]}' | wbi model eval models/arm7.urdf --state -",
               "its end effector's pose, Jacobian and dJ nu at q = 0")
      .example("echo '{}' | wbi model eval models/humanoid.urdf --state - --backend dart",
               "the humanoid at q = 0, computed by DART");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const std::string state_file = opts.get("state");
  const auto backend = load_backend(opts);
  const nlohmann::json state = inspect::read_state(state_file);
  nlohmann::json out;
  try {
    out = inspect::evaluate_state(*backend, state);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

// ---------------------------------------------------------------- bench

int run_bench(Args args) {
  Options opts(
      "wbi model bench URDF [--backend wbi|dart] [--fixed-base] [--armature j=v,...] [--json]",
      "Time the main operations of a model backend on a URDF: median ns per call over\n"
      "batches of calls cycling through random states. forward_kinematics_ns is the pose\n"
      "of the Jacobian frame from q (wbi: all bodies; dart: the frame's ancestors, lazily).\n"
      "Also see bench/model (Google Benchmark suite wbi_bench_model).");
  opts.positional("URDF", "the robot description (.urdf)")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order)")
      .option("armature", "LIST", kArmatureHelp)
      .option("states", "N", "number of random states", "101")
      .option("batch", "N", "calls per batch", "200")
      .option("backend", "NAME", kBackendHelp, "wbi")
      .flag("json", "print JSON instead of text");
  opts.example(kBenchExample, "the arm's algorithms, timed")
      .example("wbi model bench models/humanoid.urdf --backend dart --json",
               "the humanoid's, computed by DART, as JSON");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const long states = opts.get_int("states");
  const long batch = opts.get_int("batch");
  if (states < 1 || batch < 1) {
    throw UsageError("--states and --batch must be at least 1");
  }
  const auto backend = load_backend(opts);
  const inspect::TimingReport report =
      inspect::time_algorithms(*backend, static_cast<int>(states), static_cast<int>(batch));
  if (opts.has("json")) {
    std::cout << inspect::timing_json(report).dump(2) << "\n";
  } else {
    inspect::write_timing_text(std::cout, report);
  }
  return kExitOk;
}

// ---------------------------------------------------------------- mjcf

// --robot-config FILE: what the MuJoCo engine loads for that robot config, whose
// URDF must be the URDF given; --fixed-base still fixes the base.
inspect::MjcfExport robot_config_export(const Options& opts, const std::string& config_file) {
  if (opts.has("joints")) {
    throw UsageError("--joints: a robot config describes the whole robot (no reduced model)");
  }
  wbi::robot_config::RobotConfig config = wbi::robot_config::load_robot_config(config_file);
  namespace fs = std::filesystem;
  if (fs::weakly_canonical(opts.get("URDF")) != fs::weakly_canonical(config.urdf)) {
    throw UsageError("URDF '" + opts.get("URDF") + "' is not the robot config's (" + config.urdf +
                     ")");
  }
  config.fixed_base = config.fixed_base || opts.has("fixed-base");
  inspect::MjcfExport exported;
  exported.model = wbi::mujoco_sim::robot_model(config);
  exported.options = wbi::mujoco_sim::robot_mjcf(config, exported.model, config_file).options;
  return exported;
}

int run_mjcf(Args args) {
  Options opts(
      "wbi model mjcf URDF -o FILE|- [--robot-config FILE] [--fixed-base] [--joints a,b,...]\n"
      "               [--welded a,b,...] [--timestep S] [--integrator NAME]",
      "Write the model as MJCF (MuJoCo's XML) that MuJoCo loads as the same multibody as\n"
      "wbi's model library: the bodies after lumping fixed joints, joints with axes and\n"
      "limits, inertias written to the last bit, and a free joint on the root link's frame\n"
      "when the base floats. Non-physical link inertias (MuJoCo rejects them) are replaced\n"
      "by the nearest physical ones, as LoadOptions::repair_inertia does in wbi's model,\n"
      "and each such link is named on stderr. With --robot-config, what the MuJoCo engine\n"
      "loads for that robot config: its joints' armature, damping and friction, contact\n"
      "geometry and ground, IMU and F/T sites and sensors (F/T child links welded as\n"
      "bodies of their own), and its mujoco: timestep and integrator. See\n"
      "model_service/mjcf/README.md and robot_side/mujoco_sim/README.md.");
  opts.positional("URDF", "the robot description (.urdf)")
      .option("output", "FILE", "where to write the MJCF (also -o FILE); '-' for standard output")
      .option("robot-config", "FILE",
              "a robot config (deploy/robots/*.yaml) whose URDF is URDF: write what the MuJoCo "
              "engine loads")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated); lock the rest at 0")
      .option("welded", "LIST",
              "links lumped by fixed joints to keep as MuJoCo bodies of their own, welded to "
              "their parent (comma-separated; e.g. the child links of F/T sensors)")
      .option("timestep", "SECONDS",
              "MuJoCo's integration step (default 0.001, or the robot config's)")
      .option("integrator", "NAME",
              "MuJoCo's integrator: euler, rk4 or implicit (default euler, or the robot "
              "config's)");
  opts.example(kMjcfExample, "the arm for MuJoCo")
      .example(
          "wbi model mjcf models/humanoid.urdf --robot-config deploy/robots/humanoid.yaml "
          "-o humanoid.xml",
          "what the MuJoCo engine loads for the humanoid: contacts, ground, sensors");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  if (!opts.has("output")) {
    throw UsageError("missing -o FILE (-o - writes to standard output)");
  }
  inspect::MjcfExport exported;
  try {
    if (const auto config_file = opts.get_optional("robot-config")) {
      exported = robot_config_export(opts, *config_file);
    } else {
      exported = inspect::mjcf_export_from_urdf(opts.get("URDF"), load_options(opts));
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  wbi::mjcf::MjcfOptions& options = exported.options;
  if (const auto timestep = opts.get_optional("timestep")) {
    options.timestep = opts.get_double("timestep");
    if (!(options.timestep > 0.0)) {
      throw UsageError("--timestep must be > 0");
    }
  }
  if (const auto integrator = opts.get_optional("integrator")) {
    const auto parsed = enum_from_name_any_case<Integrator>(*integrator);
    if (!parsed) {
      throw UsageError("--integrator: unknown '" + *integrator + "' (euler, rk4 or implicit)");
    }
    options.integrator = *parsed;
  }
  if (const auto welded = opts.get_optional("welded")) {
    for (const std::string& link : split_list(*welded, "welded", "link")) {
      options.welded_links.push_back(link);
    }
  }
  std::string xml;
  try {
    xml = wbi::mjcf::write_mjcf(exported.model, options);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  for (const std::string& link : exported.model.repaired_inertia_links) {
    std::cerr << "wbi model mjcf: link '" << link
              << "': non-physical inertia replaced by the nearest physical one (the same as "
                 "wbi's model with LoadOptions::repair_inertia)\n";
  }
  const std::string output = opts.get("output");
  if (output == "-") {
    std::cout << xml;
    return kExitOk;
  }
  inspect::save_text_file(xml, output);
  std::cout << "wrote " << output << ": ";
  inspect::write_export_summary(std::cout, exported);
  std::cout << "\n";
  return kExitOk;
}

}  // namespace

int run_model(Args args) {
  return run_subcommand(
      "model", args,
      {
          {"info", "joints with limits, frames, bodies after lumping, total mass, base kind",
           kInfoExample, run_info},
          {"eval", "M, h, G, CoM, centroidal momentum and frame quantities at a JSON state",
           kEvalExample, run_eval},
          {"bench", "median ns per call of the main algorithms at random states", kBenchExample,
           run_bench},
          {"mjcf", "write the model as MJCF, MuJoCo's XML, the same multibody to the last bit",
           kMjcfExample, run_mjcf},
      },
      kModelNotes);
}

}  // namespace wbi::cli
