// wbi_test_fault_recording: what a recording made through faults says about
// them (tests/faults: balance_faults.sh, process_faults.sh). It reads MCAP files of
// `wbi record` (several when the recorder itself was restarted), merged by
// log time, and checks:
//  - per fault (EVENTS: lines `LABEL START BACK`, system-clock seconds: the
//    fault began, the component was back): the CoM of the ground truth
//    (wbi/ROBOT/ground_truth through the project's model of the robot, URDF)
//    against the controller's CoM reference of the same tick
//    (wbi/ROBOT/signals/CONTROLLER, values 3-5, matched by source stamp;
//    taken back to the world when a new estimator changed the frame, and
//    any jump of it counted as deviation):
//    worst error from START to BACK + 2 s under BOUND, under 1 cm from
//    BACK + 2 s on;
//  - samples: the ground truth counted by its Header.seq, per incarnation of
//    the robot (its sequence restarts); the samples missing around a fault
//    (a gap that opens from 1 s before it starts — a killed recorder loses
//    what it had not flushed — to the next fault) are at most its outage + 1 s
//    at the stream's rate, and at most 1 s of them elsewhere.
// A sample's log time is when the recorder received it; matching by stamp
// keeps a late delivery (a stopped recorder catching up) correct.
// CONTROLLER and URDF "-": the samples only (a robot without a CoM reference).
// Prints one line per fault and one for the samples; exit 0 pass, 1 fail, 2 usage.
//   wbi_test_fault_recording ROBOT CONTROLLER URDF EVENTS BOUND_M FILE.mcap...
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <wbi/msg/descriptionPubSubTypes.h>
#include <wbi/msg/sensorsPubSubTypes.h>
#include <wbi/msg/signalsPubSubTypes.h>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <wbi/dds/cdr.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/model/com.hpp>
#include <wbi/model/configuration.hpp>
#include <wbi/model/urdf.hpp>

namespace {

constexpr double kRecovered = 0.01;  // [m] CoM error of a recovered robot
constexpr double kRecoveryS = 2.0;   // [s] after the component's return
constexpr double kLossSlackS = 1.0;  // [s] of samples a fault may cost beyond the outage
// A change of frame is a jump of the CoM estimate that no motion explains:
// over 1 mm beyond what kFastestCom covers between the two ticks (the
// sinusoid peaks at 0.063 m/s; 1 mm a tick is 1 m/s). A new estimator's
// offset is wherever its base happened to be (0-5 cm): the former threshold,
// 1 cm a tick, took an offset under 1 cm for a jump of the reference (counted
// as deviation) and for a CoM error, about 1 cm in all in some runs.
constexpr double kFrameJumpM = 0.001;        // [m]
constexpr double kFastestCom = 0.25;         // [m/s]
constexpr std::int64_t kMatchNs = 10000000;  // [ns] a reference this much older still matches

// A sample cut short (a killed recorder's last chunk is dropped whole) does not decode.
template <class T>
bool decode(std::span<const std::uint8_t> bytes, T& out) {
  return wbi::dds::decode_cdr(bytes, out);
}

struct Truth {
  double t = 0.0;  // log time [s], system clock
  std::uint64_t seq = 0;
  std::int64_t stamp = 0;  // source stamp (simulated time) [ns]
  int epoch = 0;           // simulations before this one (a restarted robot's stamps restart)
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
};

struct Reference {
  std::int64_t stamp = 0;  // of the estimate the controller answered: a tick's stamp
  int epoch = 0;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();       // the reference, estimator's frame
  Eigen::Vector3d estimate = Eigen::Vector3d::Zero();  // the controller's CoM, the same frame
  double t = 0.0;                                      // log time [s]
  Eigen::Vector3d world = Eigen::Vector3d::Zero();     // the reference in the world (below)
  double jump = 0.0;  // of `world` since the reference before it [m]
  bool operator<(const Reference& o) const {
    return epoch != o.epoch ? epoch < o.epoch : stamp < o.stamp;
  }
};

// The epoch of a stream's sample: one more each time its stamps go back.
struct EpochCounter {
  int epoch = 0;
  std::int64_t last = -1;
  int next(std::int64_t stamp) {
    epoch += last >= 0 && stamp < last ? 1 : 0;
    last = stamp;
    return epoch;
  }
};

struct Event {
  std::string label;
  double start = 0.0;
  double back = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: %s ROBOT CONTROLLER URDF EVENTS BOUND_M FILE.mcap...\n", argv[0]);
    return 2;
  }
  const std::string robot = argv[1];
  const std::string truth_topic = "wbi/" + robot + "/ground_truth";
  const std::string signals_topic = "wbi/" + robot + "/signals/" + argv[2];
  const std::string description_topic = "wbi/" + robot + "/description";
  const double bound = std::stod(argv[5]);
  try {
    const bool with_com = std::string(argv[2]) != "-";
    std::optional<wbi::model::Model> model;
    std::optional<wbi::model::Data> data;
    if (with_com) {
      model.emplace(wbi::model::load_urdf_file(argv[3]));
      data.emplace(*model);
    }
    std::vector<Event> events;
    {
      std::ifstream in(argv[4]);
      Event e;
      while (in >> e.label >> e.start >> e.back) {
        events.push_back(e);
      }
    }

    wbi::msg::RobotDescription description;
    wbi::msg::GroundTruth truth;
    wbi::msg::Signals signals;
    std::vector<int> model_joint;  // description's joint k → the model's joint index
    std::vector<Truth> truths;
    std::vector<Reference> references;
    Eigen::VectorXd s(with_com ? model->n_joints : 0);
    EpochCounter truth_epochs;
    EpochCounter reference_epochs;
    // Files in the order of their first message: a restarted recorder's come after.
    std::vector<std::pair<std::uint64_t, std::string>> files;
    for (int f = 6; f < argc; ++f) {
      const wbi::mcap::Reader reader(argv[f]);
      auto cursor = reader.messages(wbi::mcap::Order::log_time);
      const auto* m = cursor.next();
      files.emplace_back(m != nullptr ? m->log_time : 0, argv[f]);
    }
    std::sort(files.begin(), files.end());
    for (const auto& [first_time, file] : files) {
      const wbi::mcap::Reader reader(file);
      auto cursor = reader.messages(wbi::mcap::Order::log_time);
      while (const auto* m = cursor.next()) {
        const double t = 1e-9 * static_cast<double>(m->log_time);
        if (with_com && m->channel->topic == description_topic && model_joint.empty() &&
            decode(m->data, description)) {
          for (const auto& name : description.joint_names()) {
            const auto it =
                std::find(model->joint_name.begin(), model->joint_name.end(), name.to_string());
            if (it == model->joint_name.end()) {
              std::fprintf(stderr, "%s: joint '%s' of the description is not in %s\n", file.c_str(),
                           name.to_string().c_str(), argv[3]);
              return 1;
            }
            model_joint.push_back(static_cast<int>(it - model->joint_name.begin()));
          }
        } else if (m->channel->topic == signals_topic && decode(m->data, signals) &&
                   signals.values().size() >= 6) {
          const auto& v = signals.values();
          const auto stamp = signals.header().stamp_ns();
          Reference ref;
          ref.stamp = stamp;
          ref.epoch = reference_epochs.next(stamp);
          ref.com = {v[3], v[4], v[5]};
          ref.estimate = {v[0], v[1], v[2]};
          ref.t = t;
          references.push_back(ref);
        } else if (m->channel->topic == truth_topic && decode(m->data, truth)) {
          Truth sample;
          sample.t = t;
          sample.seq = truth.header().seq();
          sample.stamp = truth.header().stamp_ns();
          sample.epoch = truth_epochs.next(sample.stamp);
          if (with_com) {
            if (truth.q().size() != model_joint.size()) {
              continue;  // before the description
            }
            for (std::size_t k = 0; k < model_joint.size(); ++k) {
              s[model_joint[k]] = truth.q()[k];
            }
            const auto& p = truth.base_pose().position();
            const auto& o = truth.base_pose().orientation();
            const Eigen::VectorXd q = wbi::model::make_configuration(
                *model, {p.x(), p.y(), p.z()}, Eigen::Quaterniond(o.w(), o.x(), o.y(), o.z()), s);
            sample.com = wbi::model::center_of_mass(*model, *data, q);
          }
          truths.push_back(sample);
        }
      }
    }
    if (truths.empty() || (with_com && references.empty())) {
      std::fprintf(stderr, "no ground truth (%s) or no CoM reference (%s) recorded\n",
                   truth_topic.c_str(), signals_topic.c_str());
      return 1;
    }
    std::sort(references.begin(), references.end());
    // The estimator's frame is the world's until a new estimator starts its own
    // (a legged base starts at x = y = 0): the controller's CoM estimate then
    // jumps, by more than a CoM moves in a tick (kFrameJumpM above). Those
    // jumps are summed per simulation, and the reference taken back to the
    // world; a reference that jumps there moved the robot's target: counted
    // as deviation.
    // Only between references of close ticks (the recording may have lost some).
    Eigen::Vector3d frame = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < references.size(); ++k) {
      Reference& ref = references[k];
      const Reference* before = k > 0 ? &references[k - 1] : nullptr;
      if (before != nullptr && before->epoch != ref.epoch) {
        frame.setZero();
        before = nullptr;
      }
      const bool close = before != nullptr && ref.stamp - before->stamp <= kMatchNs;
      const double motion =
          close ? kFastestCom * 1e-9 * static_cast<double>(ref.stamp - before->stamp) : 0.0;
      if (close && (ref.estimate - before->estimate).norm() > kFrameJumpM + motion) {
        frame += ref.estimate - before->estimate;
      }
      ref.world = ref.com - frame;
      ref.jump = close ? (ref.world - before->world).norm() : 0.0;
    }

    // The CoM error of each ground-truth sample: against the reference computed
    // for the newest tick at or before it (none before the controller's first).
    std::vector<double> error(truths.size(), -1.0);
    for (std::size_t i = 0; i < truths.size(); ++i) {
      Reference key;
      key.stamp = truths[i].stamp;
      key.epoch = truths[i].epoch;
      const auto after = std::upper_bound(references.begin(), references.end(), key);
      // The reference of this tick, or of one at most kMatchNs before it (a
      // tick the controller skipped); none when the recording lost them.
      if (after != references.begin() && (after - 1)->epoch == truths[i].epoch &&
          truths[i].stamp - (after - 1)->stamp <= kMatchNs) {
        error[i] = (truths[i].com - (after - 1)->world).norm();
      }
    }

    // Missing samples: the gaps in each incarnation's sequence (it starts again
    // with a new robot), each counted at the fault whose window holds it.
    std::vector<std::uint64_t> missing(events.size() + 1, 0);  // last: elsewhere
    std::uint64_t received = 0;
    double rate = 0.0;  // [samples/s], of the longest incarnation
    double longest = 0.0;
    for (std::size_t i = 0; i < truths.size();) {
      std::size_t j = i + 1;
      while (j < truths.size() && truths[j].seq > truths[j - 1].seq) {
        const std::uint64_t gap = truths[j].seq - truths[j - 1].seq - 1;
        std::size_t at = events.size();
        for (std::size_t e = 0; e < events.size() && gap > 0; ++e) {
          const double until = e + 1 < events.size() ? events[e + 1].start - 1.0 : truths.back().t;
          if (truths[j - 1].t >= events[e].start - 1.0 && truths[j - 1].t < until) {
            at = e;
          }
        }
        missing[at] += gap;
        ++j;
      }
      const double span = truths[j - 1].t - truths[i].t;
      if (span > longest) {
        longest = span;
        rate = static_cast<double>(truths[j - 1].seq - truths[i].seq) / span;
      }
      received += j - i;
      i = j;
    }
    bool pass = true;
    std::printf(
        "samples: %llu received in %d file(s), %llu missing outside the faults (allowed "
        "%.0f: 1 s at %.0f samples/s)\n",
        static_cast<unsigned long long>(received), argc - 6,
        static_cast<unsigned long long>(missing.back()), rate * kLossSlackS, rate);
    if (static_cast<double>(missing.back()) > rate * kLossSlackS) {
      std::printf("FAIL: %llu ground-truth samples missing outside the faults\n",
                  static_cast<unsigned long long>(missing.back()));
      pass = false;
    }

    for (std::size_t e = 0; e < events.size(); ++e) {
      const Event& ev = events[e];
      const double window_end = e + 1 < events.size() ? events[e + 1].start : truths.back().t;
      double worst = 0.0;
      double last_off = ev.back;  // last sample at or over 1 cm after the return
      bool settled_seen = false;  // a sample after back + 2 s
      for (std::size_t i = 0; i < truths.size(); ++i) {
        const double t = truths[i].t;
        if (error[i] < 0 || t < ev.start || t > window_end) {
          continue;
        }
        if (t <= ev.back + kRecoveryS) {
          worst = std::max(worst, error[i]);
        } else {
          settled_seen = true;
        }
        if (t >= ev.back && error[i] >= kRecovered) {
          last_off = t;
        }
      }
      for (const auto& ref : references) {
        if (ref.t >= ev.start && ref.t <= ev.back + kRecoveryS) {
          worst = std::max(worst, ref.jump);
        }
      }
      const double outage = ev.back - ev.start;
      // The stream's rate around the fault (lockstep runs as fast as the
      // machine allows): sequence numbers per second of log time over its window.
      double local_rate = rate;
      {
        const Truth* first = nullptr;
        const Truth* last = nullptr;
        for (const auto& sample : truths) {
          if (sample.t >= ev.start - 1.0 && sample.t <= window_end) {
            if (first == nullptr || sample.epoch != first->epoch) {
              first = &sample;
            }
            last = &sample;
          }
        }
        if (first != nullptr && last->t > first->t + 1.0 && last->seq > first->seq) {
          local_rate = static_cast<double>(last->seq - first->seq) / (last->t - first->t);
        }
      }
      const double allowed = local_rate * (outage + kLossSlackS);
      const double recovered_s = last_off - ev.back;
      if (!with_com) {
        std::printf("%s: outage %.2f s, %llu samples missing (allowed %.0f)\n", ev.label.c_str(),
                    outage, static_cast<unsigned long long>(missing[e]), allowed);
      } else {
        std::printf(
            "%s: outage %.2f s, worst CoM error %.4f m (bound %.3f), under 1 cm %.2f s after "
            "the return, %llu samples missing (allowed %.0f)\n",
            ev.label.c_str(), outage, worst, bound, recovered_s,
            static_cast<unsigned long long>(missing[e]), allowed);
        if (worst > bound) {
          std::printf("FAIL: %s: CoM error %.4f m over the bound %.3f m\n", ev.label.c_str(), worst,
                      bound);
          pass = false;
        }
        if (!settled_seen) {
          std::printf("FAIL: %s: no ground truth recorded from 2 s after the return on\n",
                      ev.label.c_str());
          pass = false;
        } else if (recovered_s > kRecoveryS) {
          std::printf("FAIL: %s: CoM error over 1 cm %.2f s after the return\n", ev.label.c_str(),
                      recovered_s);
          pass = false;
        }
      }
      if (static_cast<double>(missing[e]) > allowed) {
        std::printf("FAIL: %s: %llu ground-truth samples missing, more than the outage + 1 s\n",
                    ev.label.c_str(), static_cast<unsigned long long>(missing[e]));
        pass = false;
      }
    }
    return pass ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 1;
  }
}
