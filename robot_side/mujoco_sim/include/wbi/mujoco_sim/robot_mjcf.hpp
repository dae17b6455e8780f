// A robot config as MuJoCo is given it, without MuJoCo: the model (the config's
// armature, inertias repaired as MuJoCo's compiler needs) and the MJCF options
// (joint dynamics, contact geometry, ground, IMU and F/T sites, F/T child links
// welded as bodies of their own, timestep, integrator). MujocoBackend loads
// exactly this; `wbi model mjcf --robot-config` writes it.
//
// What the MJCF names, for looking things up after loading:
//   contact geometry k   geom "wbi_contact_<k>"
//   contact link l       site "wbi_link_<l>" at the link frame (contact wrenches)
//   IMU i                site "wbi_imu_<i>", sensors "wbi_imu_<i>_quat|_gyro|_accelerometer"
//   F/T sensor i         site "wbi_ft_<i>" on the sensor joint's child link,
//                        sensors "wbi_ft_<i>_force|_torque"
//   push i               site "wbi_push_<i>" at the push point
// Solver options (solref, solimp, cone, impratio) are not written: MuJoCo 2.2's
// MJCF writer here has no element for them; MujocoBackend sets them on the
// loaded model.
#pragma once

#include <string>
#include <vector>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/model.hpp>
#include <wbi/robot_config/robot_config.hpp>
#include <wbi/sim_models/sim_plan.hpp>

namespace wbi::mujoco_sim {

struct RobotMjcf {
  mjcf::MjcfOptions options;
};

// The model library's model of `config` (complete_from_urdf() done): its
// armature, repair_inertia on. Throws what the loader throws.
model::Model robot_model(const robot_config::RobotConfig& config);

// The MJCF options of `config` for `model` (robot_model(config)) and its plan
// (sim_models::make_sim_plan: contact links, F/T child links). Contacts and the
// ground are written when the plan has contacts (wbi.contact.enable: auto =
// floating base only).
RobotMjcf robot_mjcf(const robot_config::RobotConfig& config, const model::Model& model,
                     const sim_models::SimPlan& plan);
// The same, planning `config` first: throws what make_sim_plan() throws,
// std::invalid_argument "where: item: what" (an unknown frame or link, a F/T
// joint that is not fixed, a bad push).
RobotMjcf robot_mjcf(const robot_config::RobotConfig& config, const model::Model& model,
                     const std::string& where);

}  // namespace wbi::mujoco_sim
