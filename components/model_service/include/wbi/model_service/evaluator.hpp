// Evaluator: answers one ModelRequest (idl/model.idl) with a model backend
// (wbi/model/backend.hpp: the model library "wbi" or "dart"), without DDS. Used
// by the model-service component and by tests/benchmarks.
//
// Request checks, each failing with an error reply that names the culprit
// (never an exception, never silence): the robot name, the sizes of q, dq,
// nu_dot, tau, a unit base quaternion (floating base), known frames, at most
// 64 operations. dq may be empty (zero joint velocities).
//
// Every operation is evaluated at the request's one state. Allocation: none
// after warm-up, also when requests of different shapes alternate (the
// reply's results and their buffers are kept, never destroyed).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include <wbi/msg/description.h>
#include <wbi/msg/model.h>
#include <wbi/model/backend.hpp>
#include <wbi/model/data.hpp>
#include <wbi/model/model.hpp>

namespace wbi::model_service {

class Evaluator {
 public:
  // The "wbi" backend on a copy of model. robot: the name requests must carry.
  Evaluator(const model::Model& model, std::string robot);
  // Any backend; it must outlive the evaluator.
  Evaluator(model::ModelBackend& backend, std::string robot);
  Evaluator(const Evaluator&) = delete;
  Evaluator& operator=(const Evaluator&) = delete;

  // Fills reply: results in the order of the request's operations and an
  // empty error, or an error and no results. compute_ns: time spent here.
  // Does not touch reply.client_id / seq.
  void evaluate(const msg::ModelRequest& request, msg::ModelReply& reply);

  const model::Model& model() const { return model_; }
  const std::string& robot() const { return robot_; }

  // The robot description of the model (joint order, limits, base type).
  msg::RobotDescription description(const std::string& urdf_path) const;

 private:
  // owned (the Model constructor) or backend (the other) answers.
  Evaluator(std::unique_ptr<model::ModelBackend> owned, model::ModelBackend* backend,
            std::string robot);
  // Empty when the request is well-formed, else why not. Sets q_, nu_, …
  bool load(const msg::ModelRequest& request, std::string& error);
  void compute(const msg::OperationRequest& operation, int frame, msg::OperationResult& result);
  // Sets the number of results without destroying or constructing any in the
  // steady state: surplus results are parked in spare_ with their buffers
  // (constructing a generated message type is costly: it re-registers the
  // type objects of its IDL file).
  void resize_results(msg::ModelReply& reply, std::size_t count);

  std::unique_ptr<model::ModelBackend> owned_;  // set by the Model constructor
  model::ModelBackend& backend_;
  const model::Model& model_;  // backend_.model()
  std::string robot_;
  Eigen::VectorXd q_;    // [nq]
  Eigen::VectorXd nu_;   // [nv]
  Eigen::VectorXd dnu_;  // [nv] nu_dot (INVERSE_DYNAMICS)
  Eigen::VectorXd tau_;  // [nv] base forces 0, then the request's joint torques (FORWARD_DYNAMICS)
  Eigen::Vector3d gravity_;
  std::vector<model::ExternalWrench> wrenches_;       // capacity 16
  std::vector<int> frame_ids_;                        // per operation, capacity 64
  std::vector<msg::OperationResult> spare_;           // parked results, capacity 64
  std::unordered_map<std::string_view, int> frames_;  // views into model_.frame_name
};

}  // namespace wbi::model_service
