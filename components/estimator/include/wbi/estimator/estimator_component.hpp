// The estimator component (type "estimator"): the State element's source.
// For every sensor sample of wbi/<robot>/sensors it publishes a state
// estimate on wbi/<robot>/state with the sample's source stamp: q, dq and ddq
// from a derivative estimator (wbi::estimation), low-pass filtered joint
// torques and F/T, and the base state.
//
// Parameters:
//   robot            required; the robot's name
//   method           derivative estimator: kalman (default), adaptive-window, backward-difference
//   <method params>  the method's parameters in snake_case, e.g. velocity_window, process_noise
//   torque_cutoff_hz low-pass cut-off for joint torques and F/T [Hz]; 0 (default): unfiltered
//   base             fixed (default: identity pose, or base_position/base_quaternion),
//                    fixed_link (needs urdf and fixed_link), legged (IMU and both feet,
//                    needs urdf), or topic (from base_topic; nothing is published before
//                    its first sample)
//   urdf             for fixed_link and legged; relative to the deploy file
//   fixed_link       for base: fixed_link; the link assumed fixed in the world
//   base_position    [x, y, z] the base position: constant (fixed) or at start (fixed_link,
//                    legged; absent for legged: x = y = 0, the soles at z = 0)
//   base_quaternion  [w, x, y, z] likewise (legged: only its yaw, the IMU gives the rest)
//   base_topic       for base: topic; a GroundTruth topic (default wbi/<robot>/ground_truth)
//   feet, foot_force_torque, imu, load_force, unload_force, flat_ground,
//   velocity_time_constant
//                    for base: legged; see components/estimator/README.md
//
// Run-time parameters on wbi/<robot>/state/parameters (EstimatorParameter):
// "fixed_link" (text), "reset", and the method's parameters (value).
//
// Samples are processed on the DDS thread that receives them, only while
// ACTIVE; nothing is allocated per sample after the first.
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::estimator {

void register_components(runtime::Registry& registry);
// `base_drift` (base_drift_component.cpp), registered by register_components.
void register_base_drift(runtime::Registry& registry);

}  // namespace wbi::estimator
