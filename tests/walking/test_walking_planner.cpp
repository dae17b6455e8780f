// The controller type `walking_planner` without DDS: a fake robot standing
// still (its soles and CoM are what activation measures; its state's stamp
// advances 1 ms per tick), the planner's output connected to an input as the
// host chains them. The configured goal is walked start_after_s after
// activation, a goal while walking is refused with one line on stdout, and
// the walk ends at rest between the feet at the goal.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <wbi/controllers/controller.hpp>
#include <wbi/controllers/walking_plan.hpp>
#include <wbi/controllers/walking_planner.hpp>
#include <wbi/whole_body_interface.hpp>

namespace {

using namespace wbi;
using wbi::controllers::walking::kWalkReferenceSize;

[[noreturn]] void unused(const char* what) { throw Error(std::string("fake robot: ") + what); }

// Stands still: l_sole and r_sole 0.14 m apart, the CoM 0.55 m above their middle.
class FakeModel final : public Model {
 public:
  int dofs() const override { return 0; }
  const IdList& joint_list() const override { return joints_; }
  JointLimits joint_limits(int) const override { unused("joint_limits"); }
  const IdList& frame_list() const override { return frames_; }
  int frame_index(const std::string& frame) const override {
    for (std::size_t i = 0; i < frames_.size(); ++i) {
      if (frames_[i] == frame) return static_cast<int>(i);
    }
    throw Error("fake robot: no frame " + frame);
  }
  void frame_pose(const ConstVectorRef&, const Transform& world_H_base, int frame,
                  Transform& world_H_frame) override {
    world_H_frame = world_H_base;
    world_H_frame(1, 3) += frame == 0 ? 0.07 : -0.07;
  }
  void jacobian(const ConstVectorRef&, const Transform&, int, MatrixRef) override {
    unused("jacobian");
  }
  void dj_nu(const ConstVectorRef&, const Transform&, const ConstVectorRef&, const ConstVectorRef&,
             int, VectorRef) override {
    unused("dj_nu");
  }
  void mass_matrix(const ConstVectorRef&, const Transform&, MatrixRef) override {
    unused("mass_matrix");
  }
  void bias_forces(const ConstVectorRef&, const Transform&, const ConstVectorRef&,
                   const ConstVectorRef&, const Eigen::Vector3d&, VectorRef) override {
    unused("bias_forces");
  }
  void gravity_forces(const ConstVectorRef&, const Transform&, const Eigen::Vector3d&,
                      VectorRef) override {
    unused("gravity_forces");
  }
  void inverse_dynamics(const ConstVectorRef&, const Transform&, const ConstVectorRef&,
                        const ConstVectorRef&, const ConstVectorRef&, const ConstVectorRef&,
                        const Eigen::Vector3d&, VectorRef) override {
    unused("inverse_dynamics");
  }
  void centroidal_momentum(const ConstVectorRef&, const Transform&, const ConstVectorRef&,
                           const ConstVectorRef&, VectorRef) override {
    unused("centroidal_momentum");
  }
  void centroidal_momentum_matrix(const ConstVectorRef&, const Transform&, MatrixRef) override {
    unused("centroidal_momentum_matrix");
  }
  void com(const ConstVectorRef&, const Transform& world_H_base, Eigen::Vector3d& c) override {
    c = world_H_base.topRightCorner<3, 1>() + Eigen::Vector3d(0.0, 0.0, 0.55);
  }
  void com_jacobian(const ConstVectorRef&, const Transform&, MatrixRef) override {
    unused("com_jacobian");
  }

 private:
  IdList joints_;
  IdList frames_{"l_sole", "r_sole"};
};

class FakeState final : public State {
 public:
  std::int64_t now_ns = 0;
  Stamp read_estimates(EstimateKind, VectorRef, ReadMode) override { unused("read_estimates"); }
  Stamp read_estimate(EstimateKind, int, VectorRef, ReadMode) override { unused("read_estimate"); }
  Stamp read_robot_state(RobotState& state, ReadMode) override {
    state.world_H_base = Transform::Identity();
    state.world_H_base.topRightCorner<3, 1>() << 0.3, -0.2, 0.0;
    state.stamp.source_ns = now_ns;
    return state.stamp;
  }
  const IdList& external_wrench_links() const override { return none_; }
  Stamp read_base_pose(Transform&, ReadMode) override { unused("read_base_pose"); }
  void set_estimation_parameter(const std::string&, double) override {
    unused("set_estimation_parameter");
  }

 private:
  IdList none_;
};

class FakeRobot final : public WholeBodyInterface {
 public:
  void add_joints(const IdList&) override {}
  void init(std::chrono::milliseconds) override {}
  void close() override {}
  const IdList& joint_list() const override { return model_.joint_list(); }
  Actuators& actuators() override { unused("actuators"); }
  Sensors& sensors() override { unused("sensors"); }
  State& state() override { return state_; }
  Model& model() override { return model_; }
  const Model& model() const override { return model_; }
  const Sensors& sensors() const override { unused("sensors"); }
  const State& state() const override { return state_; }
  FakeState& clock() { return state_; }

 private:
  FakeModel model_;
  FakeState state_;
};

struct Hosted {
  Hosted() {
    controllers::register_walking_planner(registry);
    planner = registry.create("walking_planner");
    parameters = std::make_unique<controllers::ParameterTable>("walker", planner->parameters());
    parameters->size_for(robot.dofs());
    output = std::make_unique<controllers::ReferenceOutput>("walker/walk", planner->outputs()[0]);
    input = std::make_unique<controllers::ReferenceInput>("walking/walk", planner->outputs()[0]);
    output->connect(*input);
    controllers::ReferenceOutput* outputs[] = {output.get()};
    planner->bind_outputs(outputs);
  }
  void set(const char* name, std::vector<double> values) {
    parameters->set(parameters->index(name), values);
  }
  // One tick at time t [s]; the point the input then holds.
  Eigen::VectorXd tick(double t) {
    robot.clock().now_ns = std::llround(t * 1e9);
    EXPECT_TRUE(planner->update(t, 1e-3)) << "at t = " << t;
    const auto status = input->at(robot.clock().now_ns, [] {
      ADD_FAILURE() << "no point";
      return Eigen::VectorXd::Zero(kWalkReferenceSize);
    });
    EXPECT_EQ(status, controllers::ReferenceStatus::fresh);
    return input->position();
  }
  std::string progress() const {
    char line[160];
    planner->progress(line, sizeof line);
    return line;
  }

  FakeRobot robot;
  controllers::ControllerRegistry registry;
  std::unique_ptr<controllers::Controller> planner;
  std::unique_ptr<controllers::ParameterTable> parameters;
  std::unique_ptr<controllers::ReferenceOutput> output;
  std::unique_ptr<controllers::ReferenceInput> input;
};

TEST(WalkingPlanner, WalksTheConfiguredGoalAfterStartAfterAndRefusesOneWhileWalking) {
  Hosted h;
  EXPECT_FALSE(h.planner->commands_joints());
  ASSERT_EQ(h.planner->outputs().size(), 1u);
  EXPECT_EQ(h.planner->outputs()[0].size, kWalkReferenceSize);
  h.set("goal", {0.5, 0.0, 0.0});
  h.set("start_after_s", {0.5});
  h.planner->configure(h.robot, *h.parameters);
  RobotState measured;
  h.robot.state().read_robot_state(measured);
  h.planner->activate(measured);

  // Standing until start_after_s: the CoM and DCM where measured, both feet loaded.
  Eigen::VectorXd point = h.tick(0.1);
  EXPECT_LE((point.segment<3>(0) - Eigen::Vector3d(0.3, -0.2, 0.55)).norm(), 1e-12);
  EXPECT_LE((point.segment<3>(3) - Eigen::Vector3d(0.3, -0.2, 0.55)).norm(), 1e-12);
  EXPECT_EQ(point[14], 1.0);
  EXPECT_EQ(point[15], 1.0);
  EXPECT_EQ(h.progress(), "standing; 0 steps walked");

  testing::internal::CaptureStdout();
  h.tick(0.5);
  const std::string planned = testing::internal::GetCapturedStdout();
  EXPECT_NE(planned.find("walking_planner: goal [0.5 m, 0 m, 0 deg] planned at t = 0.500 s: 6 "
                         "steps"),
            std::string::npos)
      << planned;
  point = h.tick(0.5 + 0.6 + 0.3);  // the middle of the first single support
  EXPECT_EQ(h.progress(), "single support, step 1 of 6 (left foot swinging)");
  EXPECT_EQ(point[14], 0.0);

  h.set("goal", {0.2, 0.0, 0.0});
  testing::internal::CaptureStdout();
  h.planner->parameters_changed(*h.parameters);
  h.tick(1.5);
  const std::string refused = testing::internal::GetCapturedStdout();
  EXPECT_NE(refused.find("walking_planner: goal refused: walk_to: the robot is walking until"),
            std::string::npos)
      << refused;

  // The end: at rest between the feet, 0.5 m ahead, at the measured CoM height and width.
  point = h.tick(20.0);
  const Eigen::Vector3d left = point.segment<3>(6), right = point.segment<3>(10);
  EXPECT_NEAR((left - right).norm(), 0.14, 1e-12);
  EXPECT_LE((0.5 * (left + right) - Eigen::Vector3d(0.8, -0.2, 0.0)).norm(), 1e-12);
  EXPECT_LE((point.segment<3>(0) - Eigen::Vector3d(0.8, -0.2, 0.55)).norm(), 1e-12);
  EXPECT_LE((point.segment<3>(3) - Eigen::Vector3d(0.8, -0.2, 0.55)).norm(), 1e-9);
  EXPECT_EQ(h.progress(), "standing; 6 steps walked");
  const std::string summary = h.planner->summary();
  EXPECT_NE(summary.find("6 steps walked of 6 planned in 1 walks; 0.500 m"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("1 goals refused"), std::string::npos) << summary;
  EXPECT_FALSE(h.planner->update(20.0, 1e-3)) << "the same state twice";
}

}  // namespace
